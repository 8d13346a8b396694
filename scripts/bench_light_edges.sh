#!/usr/bin/env bash
# What the light-edge rays do to the error and the frame time (docs/ACCURACY.md, "Light edges"):
# sets up and builds (scripts/setup.sh, plus openimageio-tools for the references), then runs
# scripts/light_edges_report.py, which renders each scene of docs/ACCURACY.md with
# --light-edge-rays 0 and with the default, side by side, against the scenes' path-traced
# references (rendered with --render-references where not cached in out/reference/). Writes
# docs/accuracy/light-edges.csv and the generated block of docs/ACCURACY.md.
#
# Usage: scripts/bench_light_edges.sh [--scenes a,b] [--frames N] [--render-references] [...]
#   (every option of scripts/light_edges_report.py)
# IGI_BUILD=/path/to/build uses that build (its bin/) instead of setting up and building build/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

# shellcheck source=scripts/bench_build.sh
source "$root/scripts/bench_build.sh"
bench_build openimageio-tools

cd "$root"
exec /usr/bin/python3 "$root/scripts/light_edges_report.py" --build "$build" \
  --command "scripts/bench_light_edges.sh${*:+ $*}" "$@"
