#!/usr/bin/env bash
# Performance benchmarks of the renderer (issue 6, items 1-5), re-runnable, and the document
# they produce (docs/PERFORMANCE.md with its data and plot in docs/perf/):
#   1. distance to the limit: igi-bench per scene (client shadow rays/s vs raw rtcOccluded1/8);
#   2. end-to-end frame rate at 640 x 480 with the paper's settings, 1 and 2 local clients, and
#      the frame time split into client, network (waiting) and master time;
#   3. scaling over 1, 2, 4, 8, 16 clients, each client in its own cgroup (v1 cpu controller)
#      capped at the same fixed CPU share, so the ideal is linear in N as in the paper's Table 1;
#   4. the master's ceiling (pixels/s) with replaying clients, master threads 1 and 2;
#   5. wire bytes per pixel: the codec's figures (igi-codec-bench) and end to end;
#   and, in section 2, the same end-to-end rows at 1920 x 1080 (full HD) for the default scene
#   and the glossy interior lit by 96 small lights.
#
# Usage: scripts/bench_performance.sh [--quick] [--raw DIR] [--doc FILE]
#   --quick   a few-minute smoke run (fewer frames and clients, smaller images); its document
#             goes to out/perf-quick/PERFORMANCE.md, not docs/, unless --doc says otherwise
#   --raw     where raw outputs (stats JSON, logs) go (default out/perf or out/perf-quick)
#   --doc     the Markdown file to write (default docs/PERFORMANCE.md); its data and plot go to
#             perf/ beside it
# Environment: IGI_BUILD=/path/to/build uses that build's bin/ and skips scripts/setup.sh
#   (otherwise setup.sh installs what is missing and builds build/).
# Needs root (or a writable /sys/fs/cgroup/cpu) for the scaling section; without it the section
# runs with uncapped clients and the document says so.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

quick=0
raw=""
doc=""
while (($#)); do
  case "$1" in
    --quick) quick=1 ;;
    --raw) raw="$2"; shift ;;
    --doc) doc="$2"; shift ;;
    -h | --help) sed -n '2,22p' "$0"; exit 0 ;;
    *) echo "bench_performance.sh: unknown argument '$1' (try --help)" >&2; exit 2 ;;
  esac
  shift
done
if ((quick)); then
  raw="${raw:-$root/out/perf-quick}"
  doc="${doc:-$root/out/perf-quick/PERFORMANCE.md}"
else
  raw="${raw:-$root/out/perf}"
  doc="${doc:-$root/docs/PERFORMANCE.md}"
fi

if [ -n "${IGI_BUILD:-}" ]; then
  bin="$IGI_BUILD/bin"
else
  "$root/scripts/setup.sh" python3-matplotlib
  bin="$root/build/bin"
fi
for exe in igi-master igi-client igi-bench igi-codec-bench; do
  [ -x "$bin/$exe" ] || { echo "bench_performance.sh: $bin/$exe is missing (build first)" >&2; exit 1; }
done
# Debian's Python has matplotlib; the report needs only the standard library otherwise.
python=/usr/bin/python3
[ -x "$python" ] || python="$(command -v python3)"

say() { echo "[bench $(date +%H:%M:%S)] $*" >&2; }
die() { echo "bench_performance.sh: $*" >&2; exit 1; }

# ---------------------------------------------------------------------------------------------
# Processes and cgroups we start, cleaned up whatever happens. A process leaves `pids` once it
# has been waited for, so a recycled process id is never signalled.
pids=()
cgroups=()
tmp="$(mktemp -d /tmp/igi-perf.XXXXXX)"
cleanup() {
  local status=$?
  set +e
  for pid in "${pids[@]}"; do
    kill -0 "$pid" 2>/dev/null && kill "$pid" 2>/dev/null
  done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null; done
  for cg in "${cgroups[@]}"; do
    [ -d "$cg" ] || continue
    # Anything still inside (it should not be) goes back to the root group first.
    while read -r p; do echo "$p" >/sys/fs/cgroup/cpu/cgroup.procs 2>/dev/null; done <"$cg/cgroup.procs"
    rmdir "$cg" 2>/dev/null || echo "bench_performance.sh: could not remove cgroup $cg" >&2
  done
  rm -rf "$tmp"
  exit "$status"
}
forget() {
  local keep=() p
  for p in "${pids[@]}"; do [ "$p" = "$1" ] || keep+=("$p"); done
  pids=("${keep[@]}")
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

# Runs a command in the background under a time limit and waits for it; fails loudly with the
# tail of its log. Usage: run_logged LOG LIMIT_SECONDS cmd...
run_logged() {
  local log="$1" limit="$2"
  shift 2
  timeout -k 15 "$limit" "$@" >"$log" 2>&1 &
  local pid=$!
  pids+=("$pid")
  local status=0
  wait "$pid" || status=$?
  forget "$pid"
  if ((status)); then
    tail -n 20 "$log" >&2
    die "failed (or timed out after $limit s): $* (log: $log)"
  fi
}

# ---------------------------------------------------------------------------------------------
# Scenes: the project's default, and the shared Cornell boxes when they are there.
scene_names=(cornell-default)
scene_files=("$root/scenes/cornell/cornell.json")
shared="$root/../shared/scenes/cornell-box"
for s in CornellBox-Original CornellBox-Sphere CornellBox-Mirror; do
  if [ -f "$shared/$s.obj" ]; then
    scene_names+=("$s")
    scene_files+=("$(cd "$shared" && pwd)/$s.obj")
  else
    say "skipping $s: $shared/$s.obj is missing"
  fi
done

# Section 1 also measures the many-light interiors of issue 36, where the client's work other
# than rays weighs most: the glossy room (96 lights), the room with 133,000 triangles of
# sculptures, and the Sponza arcades (210,496 triangles, 120 lights; its meshes come from
# ../shared/scenes, hence --allow-outside-paths).
bench_names=("${scene_names[@]}" interior-glossy interior-sculptures)
bench_files=("${scene_files[@]}" "$root/scenes/interior/glossy.json"
             "$root/scenes/interior/sculptures.json")
if [ -f "$root/../shared/scenes/sponza-dabrovic/sponza.obj" ]; then
  bench_names+=(sponza-arcades)
  bench_files+=("$root/scenes/sponza/arcades.json")
else
  say "skipping sponza-arcades in section 1: ../shared/scenes/sponza-dabrovic is missing"
fi

# The paper's settings (section 5), given explicitly although they are also the defaults.
paper=(--interleave 3x3 --direct-samples 4 --indirect-vpls 18 --caustic-photons 500)

if ((quick)); then
  bench_frames=1 bench_segments=1000000 bench_repeats=1
  fps_frames=4
  fullhd_width=640 fullhd_height=360 fullhd_frames=(2 2)
  scale_counts=(1 2 4) scale_width=320 scale_height=240
  ceiling_runs=("2 640 480 24")
  stage_frames=4
  codec_rounds=2 codec_seconds=0.2
else
  bench_frames=4 bench_segments=4000000 bench_repeats=3
  fps_frames=16
  # Frames per full-HD scene (default, interior): each run a minute or two on 2 cores.
  fullhd_width=1920 fullhd_height=1080 fullhd_frames=(8 4)
  scale_counts=(1 2 4 8 16) scale_width=640 scale_height=480
  # master threads, width, height, frames
  ceiling_runs=("1 640 480 80" "2 640 480 80" "1 1280 960 30" "2 1280 960 30")
  stage_frames=30
  codec_rounds=5 codec_seconds=0.4
fi
# Each scaling client is capped at 1/16 of a core: 16 clients take one of the two cores,
# leaving the other to the master and to the machine's other users. A high cpu.shares makes
# the share also a guarantee when others load the machine (the quota still caps it).
scale_period_us=32000
scale_quota_us=2000
scale_shares=8192

rm -rf "$raw"
mkdir -p "$raw"/{bench,fps,fullhd,scaling,ceiling,codec}
meta="$raw/meta.env"
{
  echo "date=$(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "nproc=$(nproc)"
  echo "cpu_model=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')"
  echo "cpu_flags_avx2=$(grep -m1 -o -w avx2 /proc/cpuinfo || echo no)"
  echo "cpu_flags_avx512f=$(grep -m1 -o -w avx512f /proc/cpuinfo || echo no)"
  echo "mem_total=$(grep -m1 MemTotal /proc/meminfo | awk '{print $2 " kB"}')"
  echo "kernel=$(uname -r)"
  echo "git_rev=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)"
  echo "git_dirty=$(git -C "$root" status --porcelain 2>/dev/null | grep -c . || true)"
  echo "bin=$bin"
  echo "quick=$quick"
  echo "scale_period_us=$scale_period_us"
  echo "scale_quota_us=$scale_quota_us"
  echo "scale_shares=$scale_shares"
  echo "scale_width=$scale_width"
  echo "scale_height=$scale_height"
  echo "fps_frames=$fps_frames"
  echo "fullhd_width=$fullhd_width"
  echo "fullhd_height=$fullhd_height"
  echo "fullhd_frames=${fullhd_frames[*]}"
  echo "bench_frames=$bench_frames"
  echo "bench_segments=$bench_segments"
  echo "bench_repeats=$bench_repeats"
} >"$meta"
load() { echo "load_$1=$(cut -d' ' -f1-3 /proc/loadavg)" >>"$meta"; }
started=$SECONDS

# ---------------------------------------------------------------------------------------------
# 1. Distance to the limit: igi-bench on 1 thread (per core) and on every core, repeated (the
#    report takes medians: others' load comes and goes, though igi-bench's raw and client
#    measurements take turns in rounds).
load bench
for i in "${!bench_names[@]}"; do
  for threads in 1 "$(nproc)"; do
    for r in $(seq 1 "$bench_repeats"); do
      say "igi-bench ${bench_names[$i]}, $threads thread(s), run $r of $bench_repeats"
      base="$raw/bench/${bench_names[$i]}-t$threads-r$r"
      run_logged "$base.log" 600 \
        "$bin/igi-bench" --scene "${bench_files[$i]}" --allow-outside-paths --threads "$threads" \
        --frames "$bench_frames" --segments "$bench_segments" --width 640 --height 480
      # The JSON is on stdout, the log may hold warnings before it.
      sed -n '/^{/,/^}/p' "$base.log" >"$base.json"
    done
  done
done
# igi-bench renders each frame as the first after a change, which on the many-light scenes
# takes a quarter of the light samples and VPLs per point (RenderSettings::firstFrameDivisor):
# their accumulated frames, at the full 4 + 18, as well (--accumulated), on one thread.
for i in "${!bench_names[@]}"; do
  case "${bench_names[$i]}" in interior-* | sponza-*) ;; *) continue ;; esac
  for r in $(seq 1 "$bench_repeats"); do
    say "igi-bench ${bench_names[$i]}, accumulated frames, 1 thread, run $r of $bench_repeats"
    base="$raw/bench/${bench_names[$i]}-accumulated-t1-r$r"
    run_logged "$base.log" 600 \
      "$bin/igi-bench" --scene "${bench_files[$i]}" --allow-outside-paths --threads 1 \
      --frames "$bench_frames" --segments "$bench_segments" --width 640 --height 480 --accumulated
    sed -n '/^{/,/^}/p' "$base.log" >"$base.json"
  done
done

# ---------------------------------------------------------------------------------------------
# 2. End-to-end frame rate, paper settings, 640 x 480, 1 and 2 local clients (each client gets
#    nproc / clients threads; the master uses every core as well).
load fps
for i in "${!scene_names[@]}"; do
  for clients in 1 2; do
    say "igi-master ${scene_names[$i]}, $clients local client(s), $fps_frames frames"
    run_logged "$raw/fps/${scene_names[$i]}-c$clients.log" 900 \
      "$bin/igi-master" --scene "${scene_files[$i]}" --local-clients "$clients" \
      --frames "$fps_frames" --width 640 --height 480 "${paper[@]}" \
      --stats-json "$raw/fps/${scene_names[$i]}-c$clients.json"
  done
done

# The same at full HD, on the default scene and a large interior (96 small lights, glossy
# materials: the many-light case), with fewer frames.
load fullhd
fullhd_names=(cornell-default interior-glossy)
fullhd_files=("$root/scenes/cornell/cornell.json" "$root/scenes/interior/glossy.json")
for i in "${!fullhd_names[@]}"; do
  for clients in 1 2; do
    say "igi-master ${fullhd_names[$i]} at ${fullhd_width}x$fullhd_height, $clients local client(s), ${fullhd_frames[$i]} frames"
    run_logged "$raw/fullhd/${fullhd_names[$i]}-c$clients.log" 1800 \
      "$bin/igi-master" --scene "${fullhd_files[$i]}" --local-clients "$clients" \
      --frames "${fullhd_frames[$i]}" --width "$fullhd_width" --height "$fullhd_height" \
      "${paper[@]}" --stats-json "$raw/fullhd/${fullhd_names[$i]}-c$clients.json"
  done
done

# ---------------------------------------------------------------------------------------------
# 3. Scaling: N remote clients on loopback, one render thread each, each in its own cgroup
#    capped at scale_quota_us / scale_period_us of a core.
load scaling
cgroot=/sys/fs/cgroup/cpu
capped=1
probe="$cgroot/igi-perf-$$-probe"
if ! { mkdir "$probe" && echo "$scale_period_us" >"$probe/cpu.cfs_period_us" &&
  echo "$scale_quota_us" >"$probe/cpu.cfs_quota_us"; } 2>/dev/null; then
  capped=0
  say "WARNING: cannot create cgroups under $cgroot: scaling clients run UNCAPPED"
fi
[ -d "$probe" ] && rmdir "$probe"
echo "scale_capped=$capped" >>"$meta"

secret="$tmp/secret"
head -c 32 /dev/urandom | od -An -tx1 | tr -d ' \n' >"$secret"
chmod 600 "$secret"

# Frames per run grow with N so that every run does about the same wall time.
scale_frames() { if ((quick)); then echo $(($1 + 2)); else echo $((3 * $1 + 3)); fi; }

for n in "${scale_counts[@]}"; do
  frames="$(scale_frames "$n")"
  say "scaling: $n capped client(s), $frames frames at ${scale_width}x$scale_height"
  mlog="$raw/scaling/n$n-master.log"
  stats="$raw/scaling/n$n.json"
  timeout -k 15 900 "$bin/igi-master" --scene "${scene_files[0]}" --clients "$n" \
    --listen 127.0.0.1:0 --secret-file "$secret" --frames "$frames" \
    --width "$scale_width" --height "$scale_height" "${paper[@]}" --wait-seconds 120 \
    --stats-json "$stats" >"$mlog" 2>&1 &
  master=$!
  pids+=("$master")
  port=""
  # The master's shell opens the log after this one may first read it; a sed that cannot open
  # its file exits 2, which set -e and pipefail would make this script's silent exit.
  touch "$mlog"
  for _ in $(seq 1 200); do
    port="$(sed -n 's/.*listening on 127\.0\.0\.1:\([0-9][0-9]*\).*/\1/p' "$mlog" | head -n1)"
    [ -n "$port" ] && break
    kill -0 "$master" 2>/dev/null || { cat "$mlog" >&2; die "the master for $n clients died"; }
    sleep 0.1
  done
  [ -n "$port" ] || die "the master for $n clients never said which port it listens on"
  clients=()
  groups=()
  for c in $(seq 1 "$n"); do
    cg="$cgroot/igi-perf-$$-n$n-c$c"
    if ((capped)); then
      mkdir "$cg"
      cgroups+=("$cg")
      groups+=("$cg")
      echo "$scale_period_us" >"$cg/cpu.cfs_period_us"
      echo "$scale_quota_us" >"$cg/cpu.cfs_quota_us"
      echo "$scale_shares" >"$cg/cpu.shares"
    fi
    # The subshell joins the cgroup before it becomes the client, so every thread is inside.
    (
      if ((capped)); then echo "$BASHPID" >"$cg/cgroup.procs"; fi
      exec timeout -k 15 900 "$bin/igi-client" --connect "127.0.0.1:$port" --threads 1 \
        --secret-file "$secret" --reconnect-seconds 0 --log-level warn
    ) >"$raw/scaling/n$n-client$c.log" 2>&1 &
    clients+=($!)
    pids+=($!)
  done
  status=0
  wait "$master" || status=$?
  forget "$master"
  if ((status)); then
    tail -n 20 "$mlog" >&2
    die "the master with $n capped clients failed (log: $mlog)"
  fi
  for pid in "${clients[@]}"; do
    status=0
    wait "$pid" || status=$?
    forget "$pid"
    ((status == 0)) || say "a client of the $n-client run exited with $status (see $raw/scaling/)"
  done
  # How often the cap bit: proof that the share was enforced.
  if ((capped)); then
    for cg in "${groups[@]}"; do
      echo "$(basename "$cg") $(tr '\n' ' ' <"$cg/cpu.stat")"
      rmdir "$cg"
    done >"$raw/scaling/n$n-cgroups.txt"
  fi
done

# ---------------------------------------------------------------------------------------------
# 4. The master's ceiling: replaying clients resend each tile's first result, so the master's
#    decode, scatter, filter and accumulation are the bottleneck. The first frames (really
#    rendered) are left out by the report, which times the later ones from the master's log.
load ceiling
for run in "${ceiling_runs[@]}"; do
  read -r threads w h frames <<<"$run"
  say "ceiling: master threads $threads, ${w}x$h, $frames frames"
  run_logged "$raw/ceiling/t$threads-${w}x$h.log" 600 \
    "$bin/igi-master" --scene "${scene_files[0]}" --local-clients 2 --client-threads 1 \
    --replay-clients --threads "$threads" --frames "$frames" --width "$w" --height "$h" \
    "${paper[@]}" --stats-json "$raw/ceiling/t$threads-${w}x$h.json"
done

# The same work without clients or network: igi-composite-bench times each stage on one
# thread, on a synthetic frame shaped like the default scene's.
for res in "640 480" "1280 960"; do
  read -r w h <<<"$res"
  say "igi-composite-bench ${w}x$h"
  run_logged "$raw/ceiling/stages-${w}x$h.txt" 300 \
    "$bin/igi-composite-bench" --width "$w" --height "$h" --frames "$stage_frames" --rounds 3
done

# ---------------------------------------------------------------------------------------------
# 5. Wire: the codec on its synthetic typical tile (the end-to-end figures come from section 2).
load codec
say "igi-codec-bench"
run_logged "$raw/codec/codec.txt" 300 \
  "$bin/igi-codec-bench" --rounds "$codec_rounds" --seconds "$codec_seconds"

load end
echo "run_seconds=$((SECONDS - started))" >>"$meta"

# ---------------------------------------------------------------------------------------------
say "writing $doc"
command="scripts/bench_performance.sh"
((quick)) && command="$command --quick"
"$python" "$root/scripts/perf_report.py" --raw "$raw" --doc "$doc" --command "$command"
say "done in $((SECONDS - started)) s"
