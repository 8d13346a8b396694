#!/usr/bin/env bash
# Issue 35's "Must show": Dabrovic Sponza under a sun and a sky, a glTF model under each map of
# ../shared/scenes/hdri, and a spot-lit room, each rendered by IGI, our path tracer and Blender
# Cycles; the figures, side-by-side images and the relMSE-against-time curve of the sunlit
# Sponza go to docs/lights/ and to the generated block of docs/LIGHTS.md.
# scripts/lights_mustshow.py's docstring says what is rendered and compared.
#
# Installs what is missing and builds (scripts/mustshow_env.sh; SKIP_BUILD=1 skips the build).
# Renders already in build/lights_mustshow/ are reused (--rerun renders again).
# Everything heavy runs under nice -n 19.
#
# Usage: scripts/lights_mustshow.sh [--scenes cornell-spot,sponza-sunlit,spheres-studio,spheres-courtyard]
#          [--width 160] [--height 120] [--frames 256] [--pt-spp 64] [--pt-frames 64]
#          [--cycles-spp 256] [--ref-spp 1024] [--cycles-max-spp 16384] [--seconds 60] [--threads 2]
#          [--variants] [--no-curve] [--rerun] [--cycles-only] [--no-docs] [--out DIR] [--docs DIR]
#          [--build DIR]       (scripts/lights_mustshow.py --help says what each does)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
. "$root/scripts/mustshow_env.sh"
exec /usr/bin/python3 "$root/scripts/lights_mustshow.py" "$@"
