#!/usr/bin/env bash
# The GI modes while things move (docs/MODES.md, "Measurements"): sets up and builds
# (scripts/setup.sh, plus python3-matplotlib, python3-numpy and openimageio-tools), then runs
# scripts/modes_report.py, which renders each animation of scenes/cornell/ (example.anim.json,
# moving-light.anim.json, jump.anim.json) with every GI mode, each frame alone (--no-accumulate),
# and compares every frame with a path-traced reference of that frame's scene state (our path
# tracer at the same size, 1024 spp per frame, cached in out/modes/reference/ and reused): error
# (relMSE, bias) per frame, flicker where nothing moved, lag after a change, time and rays per
# frame; writes docs/modes/ (results.csv, results.md, summary.json, plots) and the generated block
# of docs/MODES.md, and prints a summary per animation and mode.
#
# Usage: scripts/bench_modes.sh [--quick] [--modes igi,spt,stream,spt-eq,stream-eq,cache,photonmap] [more options]
#   --quick           smoke run of a few minutes: the first 20 frames of each animation, a 128-spp
#                     reference, one seed; everything goes to out/modes-quick/, docs/ are not touched
#   --modes LIST      the GI modes to measure (default igi,spt,stream,spt-eq,stream-eq: the -eq
#                     ones are spt and stream with smaller pools, at about IGI's time per frame);
#                     a mode this igi-master's --gi does not accept is skipped with a message
#   --anims LIST      a subset of example,moving-light,jump
#   --width W --height H --clients N
#                     image size (default 160 x 120) and local clients (default 1)
#   --ref-spp S       reference samples per pixel per frame (default 1024)
#   --seeds LIST      seeds of the mode sessions, results averaged (default 1,2,3)
#   --max-frames N    at most N frames of each animation
# IGI_BUILD=/path/to/build uses that build (its bin/) instead of setting up and building build/.
# A full run first renders the references: 97 frames at 1024 spp and jump's 32 at 256 (about 23
# minutes on 2 idle cores, twice that while other work runs; cached, so only the first time),
# then 3 animations x 3 modes x 3 seeds of sessions (about 4 minutes): some 27 minutes the first
# time, 4 after. --ref-spp 512 halves the references' time (and doubles their noise).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

quick=0
for a in "$@"; do
  case "$a" in
    --quick) quick=1 ;;
    -h|--help)
      sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d' | sed 's/^# \{0,1\}//'
      exit 0 ;;
  esac
done

extra=(python3-matplotlib python3-numpy openimageio-tools)

# shellcheck source=scripts/bench_build.sh
source "$root/scripts/bench_build.sh"
bench_build "${extra[@]}"

args=(--build "$build" --command "scripts/bench_modes.sh $*")
if ((quick)); then
  args+=(--out "$root/out/modes-quick" --docs "")
fi
cd "$root"
# Debian's Python: matplotlib and numpy come from python3-matplotlib and python3-numpy, not from a
# pyenv python3 on PATH.
exec /usr/bin/python3 "$root/scripts/modes_report.py" "${args[@]}" "$@"
