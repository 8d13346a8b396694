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
  # Server packages the tests use (openssh-server, munge, slurmd, slurmctld) would start their
  # daemons on this machine as they install (their postinst calls invoke-rc.d); the tests run
  # their own, in their own folders. A policy-rc.d that answers 101 ("forbidden") keeps the
  # install from starting anything. Only one this script wrote is removed again.
  guard=/usr/sbin/policy-rc.d
  if [ ! -e "$guard" ]; then
    printf '#!/bin/sh\n# written by igi scripts/setup.sh for one apt-get install\nexit 101\n' |
      $sudo tee "$guard" >/dev/null
    $sudo chmod 755 "$guard"
    trap '$sudo rm -f "$guard"' EXIT
  fi
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends "${missing[@]}"
  if grep -q "written by igi scripts/setup.sh" "$guard" 2>/dev/null; then
    $sudo rm -f "$guard"
    trap - EXIT
  fi
fi

cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release
cmake --build "$root/build" -j "$(nproc)"
