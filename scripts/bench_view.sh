#!/usr/bin/env bash
# The web view's cost and latency (docs/PERFORMANCE.md, "The web view"): sets up and builds
# (scripts/setup.sh, plus chromium; scripts/setup_node.sh), then runs tests/view/view_test.js
# --bench on the default scene at 640x480 with two local clients and Debian's chromium headless:
# the time from a key press in the page to the first image that shows it (12 presses), and the
# frame rate of 40-frame runs with a page open against without (three of each, alternating).
# Writes docs/perf/view.json, the page's screenshot docs/images/view.png and the generated block
# of docs/PERFORMANCE.md (scripts/view_report.py). About 5 minutes on 2 cores.
# IGI_BUILD=/path/to/build uses that build (its bin/) instead of setting up and building build/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [ "${1:-}" = -h ] || [ "${1:-}" = --help ]; then
  sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d' | sed 's/^# \{0,1\}//'
  exit 0
fi
# shellcheck source=scripts/bench_build.sh
source "$root/scripts/bench_build.sh"
bench_build chromium
"$root/scripts/setup_node.sh"
cd "$root"
mkdir -p docs/perf docs/images out/bench-view
start=$SECONDS
node tests/view/view_test.js --bin "$build/bin" --scene scenes/cornell/cornell.json \
  --out out/bench-view --bench docs/perf/view.json --screenshot docs/images/view.png
exec python3 scripts/view_report.py --json docs/perf/view.json --doc docs/PERFORMANCE.md \
  --command "scripts/bench_view.sh" --seconds $((SECONDS - start)) --build "$build"
