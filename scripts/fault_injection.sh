#!/usr/bin/env bash
# Fault injection: rounds of a master and remote clients rendering the default scene while
# clients are killed (SIGKILL, and a new client started in their place) and stopped (SIGSTOP,
# resumed after a random pause) at random moments. Every frame each round writes is compared
# with an undisturbed run of the same frames; the script reports the faults injected and the
# frames that came out identical, and fails if any frame differs or is missing.
#
# Usage: scripts/fault_injection.sh [--rounds N] [--clients N] [--frames N] [--seed N]
# IGI_BUILD=dir uses an existing build instead of running scripts/setup.sh.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

rounds=5 clients=3 frames=60 seed=1
while (($#)); do
  case "$1" in
    --rounds) rounds="$2"; shift 2 ;;
    --clients) clients="$2"; shift 2 ;;
    --frames) frames="$2"; shift 2 ;;
    --seed) seed="$2"; shift 2 ;;
    *) echo "unknown argument: $1" >&2; exit 2 ;;
  esac
done

if [ -z "${IGI_BUILD:-}" ]; then
  "$root/scripts/setup.sh"
  IGI_BUILD="$root/build"
fi
bin="$IGI_BUILD/bin"
RANDOM=$seed

work="$(mktemp -d /tmp/igi-faults.XXXXXX)"
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill -CONT "$p" 2>/dev/null || true; kill -KILL "$p" 2>/dev/null || true; done
  wait 2>/dev/null || true
}
trap cleanup EXIT
head -c 32 /dev/urandom | base64 > "$work/secret"

scene=(--scene "$root/scenes/cornell/cornell.json" --width 160 --height 120 --log-level info)

echo "reference: $frames undisturbed frames"
"$bin/igi-master" "${scene[@]}" --local-clients 1 --frames "$frames" \
  --output-sequence "$work/reference/frame_%04d.exr" > "$work/reference.log" 2>&1

start_client() {  # round directory; prints the new client's pid
  "$bin/igi-client" --connect "127.0.0.1:$port" --threads 1 --secret-file "$work/secret" \
    --reconnect-seconds 30 --log-level warn >> "$1/clients.log" 2>&1 &
  echo $!
}

kills=0 stops=0 correct=0 wrong=0 missing=0
for ((round = 1; round <= rounds; ++round)); do
  dir="$work/round$round"
  mkdir -p "$dir"
  "$bin/igi-master" "${scene[@]}" --clients "$clients" --listen 127.0.0.1:0 \
    --secret-file "$work/secret" --read-timeout 5 --frames "$frames" \
    --output-sequence "$dir/frame_%04d.exr" > "$dir/master.log" 2>&1 &
  master=$!
  pids+=("$master")
  port=""
  touch "$dir/master.log"  # the master's shell may open it after the first read below
  for _ in $(seq 200); do
    port="$(sed -n 's/.*listening on 127\.0\.0\.1:\([0-9]*\).*/\1/p' "$dir/master.log")"
    [ -n "$port" ] && break
    sleep 0.05
  done
  [ -n "$port" ] || { echo "round $round: the master never listened" >&2; cat "$dir/master.log" >&2; exit 1; }
  running=()
  for ((c = 0; c < clients; ++c)); do running+=("$(start_client "$dir")"); done
  pids+=("${running[@]}")

  round_kills=0 round_stops=0
  while kill -0 "$master" 2>/dev/null; do
    sleep "0.$((RANDOM % 5 + 1))"
    kill -0 "$master" 2>/dev/null || break
    grep -q "rendering" "$dir/master.log" || continue  # faults once the session runs
    victim_index=$((RANDOM % ${#running[@]}))
    victim=${running[$victim_index]}
    if ((RANDOM % 2)); then
      kill -KILL "$victim" 2>/dev/null || true
      running[$victim_index]="$(start_client "$dir")"
      pids+=("${running[$victim_index]}")
      round_kills=$((round_kills + 1))
    else
      kill -STOP "$victim" 2>/dev/null || true
      (sleep "$((RANDOM % 3)).$((RANDOM % 10))"; kill -CONT "$victim" 2>/dev/null || true) &
      round_stops=$((round_stops + 1))
    fi
  done
  wait "$master" && status=0 || status=$?
  for p in "${running[@]}"; do kill -CONT "$p" 2>/dev/null || true; done

  round_correct=0 round_wrong=0 round_missing=0
  for ((f = 0; f < frames; ++f)); do
    name=$(printf 'frame_%04d.exr' "$f")
    if [ ! -f "$dir/$name" ]; then
      round_missing=$((round_missing + 1))
    elif "$bin/igi-compare" "$dir/$name" "$work/reference/$name" 2>/dev/null |
      grep -q '"rmse": 0.0,'; then
      round_correct=$((round_correct + 1))
    else
      round_wrong=$((round_wrong + 1))
    fi
  done
  echo "round $round: master exit $status, $round_kills kills, $round_stops stops;" \
    "$round_correct of $frames frames identical to the undisturbed run," \
    "$round_wrong different, $round_missing missing"
  kills=$((kills + round_kills)) stops=$((stops + round_stops))
  correct=$((correct + round_correct)) wrong=$((wrong + round_wrong))
  missing=$((missing + round_missing))
  if ((status != 0 || round_wrong || round_missing)); then
    echo "  logs kept in $dir" >&2
    trap - EXIT
    cleanup
    exit 1
  fi
done

echo "fault injection: $rounds rounds, $((kills + stops)) faults injected ($kills kills, $stops stops)," \
  "$correct of $((rounds * frames)) frames completed identical to the undisturbed run"
rm -rf "$work"
