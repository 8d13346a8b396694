#!/usr/bin/env bash
# Larsen and Christensen's screen-space caustic filter against IGI's hashed-grid gather
# (docs/MODES.md, "The caustic filter against the hashed grid"): sets up and builds
# (scripts/bench_build.sh, plus python3-numpy and openimageio-tools), then runs
# scripts/caustic_filter_report.py, which renders `--gi photonmap` with either caustic filter on
# the shared CornellBox-Sphere and CornellBox-Water, judges the caustic region against our path
# tracer, and writes docs/modes/caustic-filter.{md,json} and the block of docs/MODES.md.
# About 6 minutes on 2 cores (the references, 4096 spp, cached in out/caustic-filter/).
#
# Usage: scripts/bench_caustic_filter.sh [caustic_filter_report.py options, e.g. --frames 32]
# IGI_BUILD=/path/to/build uses that build (its bin/) instead of setting up and building build/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

# shellcheck source=scripts/bench_build.sh
source "$root/scripts/bench_build.sh"
bench_build python3-numpy openimageio-tools

cd "$root"
# Debian's Python: numpy comes from python3-numpy, not from a pyenv python3 on PATH.
exec /usr/bin/python3 "$root/scripts/caustic_filter_report.py" --build "$build" \
  --command "scripts/bench_caustic_filter.sh $*" "$@"
