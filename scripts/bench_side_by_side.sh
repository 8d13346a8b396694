#!/usr/bin/env bash
# Two builds' clients against raw Embree, taking turns on the same scenes (issue 36: the non-ray
# work of many-light shading). For each scene, `igi-bench --threads 1` of BASE_BIN then of
# NEW_BIN, RUNS times in alternation (so a load that comes or goes weighs on both), and per build
# the medians of: client shadow rays / raw rtcOccluded16 per CPU second, and client CPU seconds
# per frame; then NEW's frame time over BASE's (median of the per-run ratios).
#
# igi-bench used to hand every tile of a frame to its thread pool at once, so a frame's tile
# buffers (six planes of a 32 x 32 tile: 64 KB a tile, about 20 MB a frame at 640 x 480) were
# allocated together and freed together; glibc gave the freed top of its heap back to the
# system and the next frame faulted it in again. That cost 15 to 25 % of the client CPU seconds
# on CornellBox-Original, in every build alike, and scattered from run to run. A client in a
# session, which receives its tiles a few at a time, does not pay it (igi-master
# --local-clients 1, 24 frames: 41.7 K page faults in all its processes as is, 40.9 K with the
# thresholds raised; igi-bench, 8 frames: 24 K to 29 K against 18 K). igi-bench now holds a
# few tiles at a time as a session's client does (--tiles-in-flight), but builds from before
# that still hand out every tile: so by default both builds run with glibc's trim and mmap
# thresholds raised (GLIBC_TUNABLES below), which measures the rendering alone in either;
# --default-malloc measures without.
#
# Usage: scripts/bench_side_by_side.sh BASE_BIN NEW_BIN [--runs 3] [--frames 4]
#                                      [--segments 4000000] [--width 640 --height 480]
#                                      [--default-malloc] [scene...]
# BASE_BIN and NEW_BIN are folders holding igi-bench (a build's bin/). Without scenes: the
# many-light interiors scenes/interior/glossy.json and sculptures.json, the Sponza arcades
# (scenes/sponza/arcades.json, meshes from ../shared/scenes) and the default Cornell scene.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
base="$1" new="$2"
shift 2
runs=3 frames=4 segments=4000000 width=640 height=480 default_malloc=0 scenes=()
while (($#)); do
  case "$1" in
    --runs) runs="$2"; shift 2 ;;
    --frames) frames="$2"; shift 2 ;;
    --segments) segments="$2"; shift 2 ;;
    --width) width="$2"; shift 2 ;;
    --height) height="$2"; shift 2 ;;
    --default-malloc) default_malloc=1; shift ;;
    *) scenes+=("$1"); shift ;;
  esac
done
if ((${#scenes[@]} == 0)); then
  scenes=("$root/scenes/interior/glossy.json" "$root/scenes/interior/sculptures.json"
          "$root/scenes/sponza/arcades.json" "$root/scenes/cornell/cornell.json")
fi
if ((!default_malloc)); then
  export GLIBC_TUNABLES=glibc.malloc.trim_threshold=1000000000:glibc.malloc.mmap_threshold=1000000000
fi
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
for s in "${scenes[@]}"; do
  for ((r = 0; r < runs; ++r)); do
    for side in base new; do
      bin="$base"
      [ "$side" = new ] && bin="$new"
      # The JSON from the first line that opens a brace: builds before igi-bench logged to
      # stderr printed a scene's loading warnings (the Sponza textures' names) before it.
      "$bin/igi-bench" --scene "$s" --allow-outside-paths --threads 1 --frames "$frames" \
        --segments "$segments" --width "$width" --height "$height" 2>/dev/null |
        sed -n '/^{/,$p' >"$out/$side.$r.json"
    done
  done
  python3 - "$s" "$out" "$runs" <<'EOF'
import json, statistics, sys
scene, out, runs = sys.argv[1], sys.argv[2], int(sys.argv[3])
def load(side):
    return [json.load(open(f"{out}/{side}.{r}.json")) for r in range(runs)]
base, new = load("base"), load("new")
def ratio(j): return j["client_shadow_rays_over_embree_occluded16_cpu"]
def frame(j): return j["client_cpu_seconds"] / j["client_frames"]
med = statistics.median
print(f"{scene.split('/')[-1]}: shadow/occluded16 (CPU s) base {med(map(ratio, base)):.3f} "
      f"new {med(map(ratio, new)):.3f}; client CPU s/frame base {med(map(frame, base)):.3f} "
      f"new {med(map(frame, new)):.3f}; new/base frame time "
      f"{med(frame(n) / frame(b) for b, n in zip(base, new)):.3f}; shadow rays "
      f"{base[0]['client_shadow_rays']} {new[0]['client_shadow_rays']}")
EOF
done
