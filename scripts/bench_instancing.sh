#!/usr/bin/env bash
# Instancing's memory and build time (docs/PERFORMANCE.md, "Instances"; issue 36): a master and
# one client process per run on MetalRoughSpheresNoTextures (98 nodes placing one sphere, in
# ../shared/scenes/gltf), with two builds side by side, alternated, 3 runs each: the client's
# peak resident memory, the scene build time it reports, the frame time, and the relMSE between
# the two builds' images. Usage:
#   scripts/bench_instancing.sh BASE_BIN NEW_BIN [--runs N] [--scene FILE] [--no-doc]
# BASE_BIN: a build's bin/ from before instancing (flattened); NEW_BIN: one with it (build/bin).
# Writes docs/perf/instancing.json and the generated block of docs/PERFORMANCE.md
# (scripts/bench_instancing.py). About a minute on 2 cores.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [ "${1:-}" = -h ] || [ "${1:-}" = --help ] || [ $# -lt 2 ]; then
  sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d' | sed 's/^# \{0,1\}//'
  exit 0
fi
exec python3 "$root/scripts/bench_instancing.py" "$@"
