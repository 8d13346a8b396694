#!/usr/bin/env bash
# Installs the Debian packages the project needs (only those missing; `apt-get update` once,
# only if something is missing) and builds everything in Release into build/.
# Usage: scripts/setup.sh [extra packages...]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

packages=(
  cmake g++ make pkg-config git
  libembree-dev libopenimageio-dev libglm-dev libboost-dev libzstd-dev
  nlohmann-json3-dev libtinyobjloader-dev libtinygltf-dev libcli11-dev libspdlog-dev
  libgtest-dev libsodium-dev
  "$@"
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if ((${#missing[@]})); then
  echo "installing: ${missing[*]}"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  $sudo apt-get update
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends "${missing[@]}"
fi

cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release
cmake --build "$root/build" -j "$(nproc)"
