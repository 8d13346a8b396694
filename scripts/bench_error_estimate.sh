#!/usr/bin/env bash
# How far igi-master's error estimate (docs/ERROR_ESTIMATE.md) can be trusted: sets up and builds
# (scripts/setup.sh, plus openimageio-tools for the references), then runs
# scripts/error_estimate_report.py, which accumulates each scene of docs/ACCURACY.md for 256
# frames (twice, two seeds) and sets the master's estimated relMSE after 4, 8, ..., 256 frames
# beside the noise measured between the two sessions and, where the scene's path-traced
# reference is cached (out/reference/, as bench_accuracy.sh's), the true one. Writes
# docs/accuracy/error-estimate.csv and the generated block of docs/ERROR_ESTIMATE.md.
#
# Usage: scripts/bench_error_estimate.sh [--scenes a,b] [--width W --height H] [--frames N]
#                                        [--ref-spp N --ref-frames N] [--ref DIR] [--seed S]
#                                        [--render-references]
#   --scenes          comma-separated subset of the scenes of docs/ACCURACY.md (default all)
#   --width, --height the image (default 160 x 120: the references cost a quarter of 320 x 240's)
#   --frames N        accumulated frames of each session (default 256)
#   --ref-spp N, --ref-frames N
#                     the references' spp per frame and frames, both halves together (default 64
#                     and 256: 16384 spp)
#   --ref DIR         where the cached references are (default out/reference/)
#   --seed S          igi's session seed (default 3, the second session S + 1; the references'
#                     halves use 1 and 2)
#   --render-references
#                     render the references that are not cached (minutes to an hour per scene
#                     on 2 shared cores); else those scenes get the between-sessions column only
# IGI_BUILD=/path/to/build uses that build (its bin/) instead of setting up and building build/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

# shellcheck source=scripts/bench_build.sh
source "$root/scripts/bench_build.sh"
bench_build openimageio-tools

cd "$root"
exec /usr/bin/python3 "$root/scripts/error_estimate_report.py" --build "$build" \
  --command "scripts/bench_error_estimate.sh $*" "$@"
