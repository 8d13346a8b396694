#!/usr/bin/env bash
# Issue 34's "Must show": the Khronos glTF models of ../shared/scenes/gltf in the Cornell room,
# a pair of white spheres that isolates the Principled BSDF's Burley diffuse, and Dabrovic Sponza
# with its bump maps, each rendered by IGI, our path tracer and Blender Cycles; the figures and
# side-by-side images go to docs/materials/ and to the generated block of docs/MATERIALS.md.
# scripts/materials_mustshow.py's docstring says what is rendered and compared.
#
# Installs what is missing and builds (scripts/mustshow_env.sh; SKIP_BUILD=1 skips the build).
# Renders already in build/materials_mustshow/ are reused (--rerun renders again). Everything
# heavy runs under nice -n 19.
#
# Usage: scripts/materials_mustshow.sh [--scenes burley-spheres,metal-rough-spheres,...]
#          [--width 80] [--height 60] [--frames 256] [--pt-spp 64] [--pt-frames 64]
#          [--cycles-spp 256] [--ref-spp 2048] [--threads 2] [--rerun] [--cycles-only] [--no-docs]
#          [--out DIR] [--docs DIR] [--build DIR]   (scripts/materials_mustshow.py --help)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
. "$root/scripts/mustshow_env.sh"
exec /usr/bin/python3 "$root/scripts/materials_mustshow.py" "$@"
