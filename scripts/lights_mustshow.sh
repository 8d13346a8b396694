#!/usr/bin/env bash
# Issue 35's "Must show": Dabrovic Sponza under a sun and a sky, a glTF model under each map of
# ../shared/scenes/hdri, and a spot-lit room, each rendered by IGI, our path tracer and Blender
# Cycles; the figures, side-by-side images and the relMSE-against-time curve of the sunlit
# Sponza go to docs/lights/ and to the generated block of docs/LIGHTS.md.
# scripts/lights_mustshow.py's docstring says what is rendered and compared.
#
# Installs what is missing (Blender, numpy for Blender's glTF importer, matplotlib, OpenImageIO's
# Python module and tools) and builds igi-master, igi-client and igi-compare in build/ unless
# SKIP_BUILD=1. Renders already in build/lights_mustshow/ are reused (--rerun renders again).
# Everything heavy runs under nice -n 19.
#
# Usage: scripts/lights_mustshow.sh [--scenes cornell-spot,sponza-sunlit,spheres-studio,spheres-courtyard]
#          [--width 160] [--height 120] [--frames 256] [--pt-spp 64] [--pt-frames 64]
#          [--cycles-spp 256] [--ref-spp 1024] [--cycles-max-spp 16384] [--seconds 60] [--threads 2]
#          [--variants] [--no-curve] [--rerun] [--cycles-only] [--no-docs] [--out DIR] [--docs DIR]
#          [--build DIR]       (scripts/lights_mustshow.py --help says what each does)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
need=()
command -v blender >/dev/null || need+=(blender)
command -v oiiotool >/dev/null || need+=(openimageio-tools)
/usr/bin/python3 -c 'import numpy' 2>/dev/null || need+=(python3-numpy)
/usr/bin/python3 -c 'import matplotlib' 2>/dev/null || need+=(python3-matplotlib)
/usr/bin/python3 -c 'import OpenImageIO' 2>/dev/null || need+=(python3-openimageio)
if [ ${#need[@]} -gt 0 ]; then
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  $sudo apt-get update
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y "${need[@]}"
fi
if [ "${SKIP_BUILD:-0}" != 1 ]; then
  nice -n 19 cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release >/dev/null
  nice -n 19 cmake --build "$root/build" -j2 --target igi-master igi-client igi-compare
fi
blender --version | head -n 1
exec /usr/bin/python3 "$root/scripts/lights_mustshow.py" "$@"
