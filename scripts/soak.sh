#!/usr/bin/env bash
# Soak: one live session for --minutes M doing, all at once and at random, what users do: the
# camera moved and an object, the light and a material changed through the control port
# (igi-ctl), an animation running (the mirror box turns for 100 frames in every 400), the web
# view open in headless chromium and reloaded now and then, clients killed (SIGKILL), stopped
# (SIGSTOP, resumed after up to 3 s), joining and leaving. Two "steady" clients are only ever
# stopped and resumed, so that their memory can be followed for the whole session; the others
# churn. Every --interval seconds it records the master's and each client's resident memory
# (VmRSS), open file descriptors (/proc/PID/fd), threads and the frame rate (igi-ctl status).
# At the end it stops the session (igi-ctl stop) and checks, after --warmup minutes:
#   - memory growth (least-squares slope) below --max-slope MB per hour (default 1) for the
#     master and every client that lived through at least half of that time;
#   - descriptors and threads flat (the last third of the samples never above the maximum
#     of the first two thirds, for the master and the steady clients);
#   - a clean exit: the master exits 0, every client ends with it, and its --stats-json is
#     valid JSON with every frame (indices 0 to n-1, none missing).
# Frames are not compared with an undisturbed run here (scripts/fault_injection.sh does that):
# random numbers follow the frame number, so a still period at frame 100,000 would need an
# undisturbed run of 100,000 frames.
# The steady clients' heap in use and held (glibc's figures, which each logs every 20 s) are
# reported beside their resident memory: a leak grows the first, a high water only the second.
# It writes OUT/samples.csv, OUT/summary.md (table) and OUT/soak.png (plot), via
# scripts/soak_report.py (matplotlib, Debian's python3-matplotlib), and exits 1 if a check fails.
#
# Usage: scripts/soak.sh [--minutes M] [--clients N] [--interval S] [--warmup W] [--seed N]
#                        [--max-slope MB_PER_HOUR] [--out DIR]
#   --clients N: clients at the start (2 steady + N-2 churning; at least 2; default 4)
#   --warmup W: minutes left out of the checks (default: a sixth of the run, at least 1)
# Sets up and builds first (scripts/setup.sh, plus chromium and python3-matplotlib);
# IGI_BUILD=dir uses that build (its bin/) instead.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [ "${1:-}" = -h ] || [ "${1:-}" = --help ]; then
  sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d' | sed 's/^# \{0,1\}//'
  exit 0
fi

minutes=10 clients=4 interval=5 warmup="" seed=1 max_slope=1 out="$root/out/soak"
while (($#)); do
  case "$1" in
    --minutes) minutes="$2"; shift 2 ;;
    --clients) clients="$2"; shift 2 ;;
    --interval) interval="$2"; shift 2 ;;
    --warmup) warmup="$2"; shift 2 ;;
    --seed) seed="$2"; shift 2 ;;
    --max-slope) max_slope="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    *) echo "unknown argument: $1" >&2; exit 2 ;;
  esac
done
((clients >= 2)) || { echo "--clients must be at least 2 (the steady ones)" >&2; exit 2; }
[ -n "$warmup" ] || warmup=$(awk -v m="$minutes" 'BEGIN { print (m / 6 > 1 ? m / 6 : 1) }')

# shellcheck source=scripts/bench_build.sh
source "$root/scripts/bench_build.sh"
bench_build chromium python3-matplotlib
bin="$build/bin"
RANDOM=$seed
mkdir -p "$out"
out="$(cd "$out" && pwd)"
work="$(mktemp -d /tmp/igi-soak.XXXXXX)"
pids=()
chromium_pid=""
sampler_pid=""
cleanup() {
  [ -n "$sampler_pid" ] && kill "$sampler_pid" 2>/dev/null || true
  [ -n "$chromium_pid" ] && kill "$chromium_pid" 2>/dev/null || true
  for p in "${pids[@]}"; do kill -CONT "$p" 2>/dev/null || true; kill -KILL "$p" 2>/dev/null || true; done
  wait 2>/dev/null || true
}
trap cleanup EXIT
head -c 32 /dev/urandom | base64 > "$work/secret"

# The animation: the mirror box turns during frames 400 k .. 400 k + 100, for as many frames as a
# session of this length can render at 1,000 frames per second, or up to the last frame an
# animation key may name (1,000,000; a run of 17 minutes or more reaches it and then holds
# the box still).
/usr/bin/python3 - "$work/soak.anim.json" "$minutes" <<'EOF'
import json, sys
keys, frame, angle = [], 0, -32
while frame + 100 <= min(float(sys.argv[2]) * 60 * 1000, 1000000):
    keys += [{"frame": frame, "rotate_deg": [0, angle, 0]},
             {"frame": frame + 100, "rotate_deg": [0, angle + 90, 0]}]
    frame, angle = frame + 400, angle + 90
json.dump({"objects": {"mirror_box": keys}}, open(sys.argv[1], "w"))
EOF

"$bin/igi-master" --scene "$root/scenes/cornell/cornell.json" --width 160 --height 120 \
  --frames 0 --clients "$clients" --listen 127.0.0.1:0 --secret-file "$work/secret" \
  --read-timeout 5 --control 127.0.0.1:0 --view 127.0.0.1:0 --animation "$work/soak.anim.json" \
  --stats-json "$work/stats.json" --log-level info > "$work/master.log" 2>&1 &
master=$!
pids+=("$master")
touch "$work/master.log"
port="" control="" view=""
for _ in $(seq 600); do
  port="$(sed -n 's/.*listening on 127\.0\.0\.1:\([0-9]*\).*/\1/p' "$work/master.log" | head -1)"
  control="$(sed -n 's/.*control commands on 127\.0\.0\.1:\([0-9]*\).*/\1/p' "$work/master.log" | head -1)"
  view="$(sed -n 's/.*view on \(http:[^ ]*\).*/\1/p' "$work/master.log" | head -1)"
  [ -n "$port" ] && [ -n "$control" ] && [ -n "$view" ] && break
  sleep 0.1
done
[ -n "$port" ] && [ -n "$control" ] && [ -n "$view" ] ||
  { echo "the master never listened" >&2; cat "$work/master.log" >&2; exit 1; }
ctl() { "$bin/igi-ctl" --connect "127.0.0.1:$control" "$@" >> "$work/ctl.log" 2>&1 || true; }

# name pid, one line per client started: the sampler follows every one still alive.
roster="$work/roster"
echo "master $master" > "$roster"
serial=0
start_client() {  # name [log level] [log file]; sets $started
  "$bin/igi-client" --connect "127.0.0.1:$port" --threads 1 --secret-file "$work/secret" \
    --reconnect-seconds 0 --log-level "${2:-warn}" >> "${3:-$work/clients.log}" 2>&1 &
  started=$!
  disown "$started"  # killed on purpose: no "Killed" line from the shell
  pids+=("$started")
  echo "$1 $started" >> "$roster"
}
steady=()
# The steady clients log at debug: their heap lines ("heap: ... MB in use"), every 20 s, tell a
# leak (the heap in use grows) from the allocator's high water (only resident memory does).
for i in 1 2; do
  start_client "steady$i" debug "$work/steady$i.log"; steady+=("$started")
done
churn=()
for ((i = 2; i < clients; ++i)); do
  serial=$((serial + 1)); start_client "churn$serial"; churn+=("$started")
done

# The sampler: every $interval s, one row per live process.
samples="$out/samples.csv"
echo "seconds,name,pid,rss_kb,fds,threads,frames_done" > "$samples"
t0=$(date +%s.%N)  # the samples' and the heap lines' time 0
(
  set +e  # a failed query (a process gone between two reads) must not end the sampler
  while :; do
    t=$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }')
    frames="$("$bin/igi-ctl" --connect "127.0.0.1:$control" status 2>/dev/null |
      sed -n 's/.*"frames_done":\([0-9]*\).*/\1/p')"
    # A pid is the latest roster entry's: a dead client's pid may be reused by a later client,
    # or by any other process of the machine, which is not sampled (its name is not ours).
    declare -A who=()
    while read -r name pid; do who[$pid]=$name; done < "$roster"
    for pid in "${!who[@]}"; do
      name=${who[$pid]}
      case "$(cat "/proc/$pid/comm" 2>/dev/null)" in igi-master|igi-client) ;; *) continue ;; esac
      [ -r "/proc/$pid/status" ] || continue
      rss=$(awk '/^VmRSS/{print $2}' "/proc/$pid/status" 2>/dev/null) || continue
      threads=$(awk '/^Threads/{print $2}' "/proc/$pid/status" 2>/dev/null) || continue
      fds=$(ls "/proc/$pid/fd" 2>/dev/null | wc -l)
      [ -n "$rss" ] && echo "$t,$name,$pid,$rss,$fds,$threads,${frames:-}" >> "$samples"
    done
    sleep "$interval"
  done
) &
sampler_pid=$!

# The web view in headless chromium; a reload is a new tab on the page and the old one closed.
chromium_dir="$work/chromium"
"${IGI_CHROMIUM:-/usr/bin/chromium}" --headless=new --no-sandbox --disable-gpu \
  --user-data-dir="$chromium_dir" --remote-debugging-port=0 about:blank > "$work/chromium.log" 2>&1 &
chromium_pid=$!
cdp=""
for _ in $(seq 300); do
  cdp="$(sed -n 's|.*DevTools listening on ws://127\.0\.0\.1:\([0-9]*\)/.*|\1|p' "$work/chromium.log")"
  [ -n "$cdp" ] && break
  sleep 0.1
done
tab=""
reload_view() {
  [ -n "$cdp" ] || return 0
  local new
  new="$(curl -s -X PUT "http://127.0.0.1:$cdp/json/new?$view" | sed -n 's/.*"id": *"\([^"]*\)".*/\1/p')"
  [ -n "$tab" ] && curl -s "http://127.0.0.1:$cdp/json/close/$tab" > /dev/null || true
  tab="$new"
}
reload_view

rnd() {  # a random number in [lo, hi) with 3 decimals
  awk -v s="$RANDOM" -v lo="$1" -v hi="$2" 'BEGIN { srand(s); printf "%.3f", lo + (hi - lo) * rand() }'
}
declare -A did=([camera]=0 [object]=0 [light]=0 [material]=0 [kill]=0 [stop]=0 [join]=0 [leave]=0
  [reload]=0 [still]=0)
end=$((SECONDS + minutes * 60))
echo "soak: $minutes min, $clients clients, samples every $interval s into $samples (work: $work)"
while ((SECONDS < end)); do
  sleep "0.$((RANDOM % 9 + 1))"
  case $((RANDOM % 20)) in
    0 | 1 | 2) ctl camera --position "$(rnd -0.6 0.6)" "$(rnd 0.7 1.3)" "$(rnd 2.8 3.6)" \
      --look-at 0 1 0 --fov-y "$(rnd 32 48)"; did[camera]=$((did[camera] + 1)) ;;
    3 | 4) ctl object glass_ball --translate "$(rnd -0.5 0.5)" 0.36 "$(rnd -0.2 0.5)"
      did[object]=$((did[object] + 1)) ;;
    5 | 6) ctl light ceiling_light --radiance "$(rnd 5 20)" "$(rnd 5 20)" "$(rnd 5 20)"
      did[light]=$((did[light] + 1)) ;;
    7 | 8) ctl material red --diffuse "$(rnd 0.1 0.9)" "$(rnd 0.05 0.3)" "$(rnd 0.05 0.3)"
      did[material]=$((did[material] + 1)) ;;
    9 | 10) # a churning client killed, a new one in its place
      if ((${#churn[@]})); then
        i=$((RANDOM % ${#churn[@]}))
        kill -KILL "${churn[$i]}" 2>/dev/null || true
        serial=$((serial + 1)); start_client "churn$serial"; churn[$i]=$started
        did[kill]=$((did[kill] + 1))
      fi ;;
    11 | 12) # any client stopped, resumed after up to 3 s
      all=("${steady[@]}" "${churn[@]}")
      victim=${all[$((RANDOM % ${#all[@]}))]}
      kill -STOP "$victim" 2>/dev/null || true
      (sleep "$((RANDOM % 3)).$((RANDOM % 10))"; kill -CONT "$victim" 2>/dev/null || true) &
      did[stop]=$((did[stop] + 1)) ;;
    13) # a new client joins (up to twice the starting number)
      if ((${#churn[@]} + 2 < 2 * clients)); then
        serial=$((serial + 1)); start_client "churn$serial"; churn+=("$started")
        did[join]=$((did[join] + 1))
      fi ;;
    14) # a client leaves for good (SIGTERM), down to one churning client
      if ((${#churn[@]} > 1)); then
        kill -TERM "${churn[-1]}" 2>/dev/null || true
        unset 'churn[-1]'
        did[leave]=$((did[leave] + 1))
      fi ;;
    15 | 16) reload_view; did[reload]=$((did[reload] + 1)) ;;
    *) sleep "$((RANDOM % 5 + 2))"; did[still]=$((did[still] + 1)) ;;  # nobody touches anything
  esac
  kill -0 "$master" 2>/dev/null || break
done

for p in "${steady[@]}" "${churn[@]}"; do kill -CONT "$p" 2>/dev/null || true; done
sleep "$interval"  # one last sample of everything undisturbed
kill "$sampler_pid" 2>/dev/null || true
sampler_pid=""
ctl stop
status=0
wait "$master" || status=$?
clients_alive=0
for p in "${steady[@]}" "${churn[@]}"; do
  for _ in $(seq 100); do kill -0 "$p" 2>/dev/null || break; sleep 0.1; done
  kill -0 "$p" 2>/dev/null && clients_alive=$((clients_alive + 1))
done
stats_ok=0
# Every frame shown, none missing: indices 0 .. n-1 in order.
/usr/bin/python3 -c "
import json, sys
frames = json.load(open(sys.argv[1]))['frames']
assert [f['index'] for f in frames] == list(range(len(frames))), 'frames missing or out of order'
print(len(frames))" "$work/stats.json" > "$work/stats.frames" 2>> "$work/master.log" && stats_ok=1

faults="camera ${did[camera]}, object ${did[object]}, light ${did[light]}, material ${did[material]}, kill ${did[kill]}, stop ${did[stop]}, join ${did[join]}, leave ${did[leave]}, view reload ${did[reload]}, still ${did[still]}"
echo "actions: $faults"
cp "$work/master.log" "$out/master.log" 2>/dev/null || true
report=0
# Debian's Python: matplotlib comes from python3-matplotlib, not from a pyenv python3 on PATH.
/usr/bin/python3 "$root/scripts/soak_report.py" --samples "$samples" --out "$out" --warmup "$warmup" \
  --max-slope "$max_slope" --minutes "$minutes" --actions "$faults" --master-exit "$status" \
  --clients-left-running "$clients_alive" --stats-ok "$stats_ok" \
  --stats-frames "$(cat "$work/stats.frames" 2>/dev/null || echo 0)" --t0 "$t0" \
  --heap-log "steady1=$work/steady1.log" --heap-log "steady2=$work/steady2.log" || report=$?
if ((report == 0)); then rm -rf "$work"; else echo "work files kept in $work" >&2; trap - EXIT; cleanup; fi
exit "$report"
