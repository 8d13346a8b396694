#!/usr/bin/env bash
# What adaptive tiles gain (docs/ERROR_ESTIMATE.md, "Adaptive tiles"): sets up and builds
# (scripts/setup.sh, plus openimageio-tools for the references), then runs
# scripts/adaptive_tiles_report.py, which measures per scene the tiles and seconds to a true
# relMSE against the path-traced reference (out/reference/, rendered when missing), with
# adaptive tiles and without. Writes docs/accuracy/adaptive-tiles.csv and the generated block of
# docs/ERROR_ESTIMATE.md.
#
# Usage: scripts/bench_adaptive_tiles.sh [--scenes a,b] [--width W --height H] [--tile-size T]
#                                        [--frames N] [--target-frames a,b] [--seed S]
#                                        [--ref-spp N --ref-frames N] [--ref DIR]
#   --scenes          comma-separated scenes of docs/ACCURACY.md (default: default,
#                     cornell-glossy, interior-diffuse: a caustic, a glossy box, an interior)
#   --width, --height the image (default 160 x 120)
#   --tile-size T     tile edge (default 8: 35 regions at 160 x 120, as 32 gives at 640 x 480)
#   --frames N        the plain session's frames, whose curve the gain is read from (default 256)
#   --target-frames   the targets: the plain session's estimate after these frames (32,64,128)
#   --ref-spp N, --ref-frames N
#                     the references' spp per frame and frames, both halves together (default 64
#                     and 64: 4096 spp, the default scene's 4 times that)
# IGI_BUILD=/path/to/build uses that build (its bin/) instead of setting up and building build/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

# shellcheck source=scripts/bench_build.sh
source "$root/scripts/bench_build.sh"
bench_build openimageio-tools

cd "$root"
exec /usr/bin/python3 "$root/scripts/adaptive_tiles_report.py" --build "$build" \
  --command "scripts/bench_adaptive_tiles.sh $*" "$@"
