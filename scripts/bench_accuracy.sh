#!/usr/bin/env bash
# Speed against accuracy of igi, its convergence, and the peer comparison (docs/ACCURACY.md): sets
# up and builds (scripts/setup.sh, plus python3-matplotlib and openimageio-tools and, with --peers,
# embree-tools and blender), then runs scripts/accuracy_report.py, which renders converged
# references with our path tracer (>= 4096 spp, cached in out/reference/, reused when present),
# sweeps igi's parameters, accumulates igi (converging and --converge off) and our path tracer
# for 60 s of render time, compares every image with igi-compare and writes docs/accuracy/
# (results.csv, results.md, summary.json, one plot per scene) and the generated blocks of
# docs/ACCURACY.md; it ends with a summary of which of the page's claims hold.
#
# Usage: scripts/bench_accuracy.sh [--quick] [--peers] [--no-sweeps] [--baseline-build DIR]
#                                  [more accuracy_report.py options, e.g. --scenes default,cornell-glossy]
#   --quick           smoke run of a few minutes: default scene, few points, weak reference, curves
#                     of 3 s; the report goes to out/accuracy-quick/report/ and docs/ are not touched
#   --peers           also Blender Cycles (doubling spp until a render takes 60 s) and the Embree
#                     pathtracer probe
#   --no-sweeps       no parameter sweeps: the convergence part only
#   --baseline-build DIR
#                     a previous build (DIR/bin/igi-master, e.g. /work/base/build): its first frame
#                     and accumulation curve at the same settings, and the ratios new / old
#   --docs DIR, --doc FILE
#                     where the report goes (default docs/accuracy/) and the document whose
#                     generated blocks are replaced (default docs/ACCURACY.md)
#   --ref DIR         where the cached references are (default out/reference/): e.g. those of
#                     another worktree, which saves their hours of path tracing
#   --seconds S       render time the accumulation and Cycles curves span (default 60)
#   --min-frames N    accumulated frames at least (default 256)
#   --ref-spp N, --ref-frames N
#                     the references' spp per frame and frames, both halves together (default
#                     64 and 256: 16384 spp)
#   --modes cache,photonmap
#                     a run of the GI modes instead: igi, each mode and our path tracer accumulated
#                     per scene (no sweeps, no claims); writes docs/accuracy/modes-WxH/ and only the
#                     block modes-WxH of docs/ACCURACY.md (e.g. with --width 1920 --height 1080)
# IGI_BUILD=/path/to/build uses that build (its bin/) instead of setting up and building build/.
# A full run with --peers and --baseline-build renders 6 scenes for 60 s each several times over,
# plus the 4096-spp references the first time: expect one to two hours on 2 shared cores.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

quick=0
peers=0
for a in "$@"; do
  case "$a" in
    --quick) quick=1 ;;
    --peers) peers=1 ;;
  esac
done

extra=(python3-matplotlib openimageio-tools)
if ((peers)); then extra+=(embree-tools blender); fi

# shellcheck source=scripts/bench_build.sh
source "$root/scripts/bench_build.sh"
bench_build "${extra[@]}"

args=(--build "$build" --command "scripts/bench_accuracy.sh $*")
if ((quick)); then
  args+=(--out "$root/out/accuracy-quick" --docs "")
fi
cd "$root"
# Debian's Python: matplotlib comes from python3-matplotlib, not from a pyenv python3 on PATH.
exec /usr/bin/python3 "$root/scripts/accuracy_report.py" "${args[@]}" "$@"
