#!/usr/bin/env bash
# The main job: sets up and builds (scripts/setup.sh), then runs a master with two local
# clients rendering the project's default scene to out/default.png and out/default.exr, with
# statistics in out/default-stats.json. Extra arguments go to igi-master.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
cd "$root"
exec build/bin/igi-master --scene scenes/cornell/cornell.json --local-clients 2 --frames 16 \
  --output out/default.png --output out/default.exr --stats-json out/default-stats.json "$@"
