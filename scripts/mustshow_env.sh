# Sourced by scripts/lights_mustshow.sh and scripts/materials_mustshow.sh (with $root set to the
# repository): installs what is missing (Blender, numpy for Blender's glTF importer, matplotlib,
# OpenImageIO's Python module and tools) and builds igi-master, igi-client and igi-compare in
# build/ unless SKIP_BUILD=1, under nice -n 19.
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
