#!/usr/bin/env bash
# Many lights (docs/PERFORMANCE.md, "Many lights"): sets up and builds (scripts/setup.sh, plus
# python3-matplotlib), then runs scripts/many_lights_report.py, which renders the interior scenes
# lit by 96 small lights (scenes/interior/diffuse.json, glossy.json, and sculptures.json with
# 133,000 more triangles) and the Sponza atrium lit by 120 small lights under its arcades
# (scenes/sponza/arcades.json, 210,000 triangles; its meshes are read from ../shared/scenes)
# with IGI and our path tracer: light samples by power or by the light tree, IGI's VPLs all
# connected or chosen per point by importance. It compares every image with a path-traced
# reference (cached in out/many-lights/reference/): relMSE, bias, SSIM and speckle against
# time; the ratios at equal time and equal error; writes docs/perf/many-lights.{json,png} and
# the generated block of docs/PERFORMANCE.md.
#
# Usage: scripts/bench_many_lights.sh [--quick] [--scenes LIST] [--variants LIST] [--seeds 1,2]
#                                     [--ref-spp 2048] [--width W --height H]
#   --quick   a smoke run (1 seed, up to 4 frames, 256-spp references) into out/many-lights-quick/;
#             docs/ are not touched
# IGI_BUILD=/path/to/build uses that build (its bin/) instead of setting up and building build/.
# A full run takes about an hour on 2 cores the first time (the references: 2048 spp, 4096 for
# the Sponza atrium), then about half that.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
for a in "$@"; do
  case "$a" in
    -h|--help)
      sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d' | sed 's/^# \{0,1\}//'
      exit 0 ;;
  esac
done
# shellcheck source=scripts/bench_build.sh
source "$root/scripts/bench_build.sh"
bench_build python3-matplotlib
cd "$root"
# Debian's Python: matplotlib comes from python3-matplotlib, not from a pyenv python3 on PATH.
exec /usr/bin/python3 "$root/scripts/many_lights_report.py" --build "$build" \
  --command "scripts/bench_many_lights.sh${*:+ $*}" "$@"
