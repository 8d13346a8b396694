#!/usr/bin/env bash
# Sets up and builds (scripts/setup.sh), builds the libFuzzer targets with clang into
# build-fuzz/ and runs their short fuzz tests, then runs every test with ctest. The main suite
# runs last, so the output ends with its summary line.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh" clang libclang-rt-14-dev chromium iproute2 \
  openssh-server openssh-client munge slurmd slurmctld slurm-client
"$root/scripts/setup_node.sh"

# Only the fuzz targets and what they link (igi_common, igi_protocol): the sanitized clang
# build of everything else would double the build time for nothing. The seed targets write the
# seeds into build-fuzz/fuzz/seeds/ from this checkout's code and files (with the tools
# make_protocol_seeds and make_scene_seeds).
CC=clang CXX=clang++ cmake -S "$root" -B "$root/build-fuzz" -DIGI_FUZZ=ON \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo
cmake --build "$root/build-fuzz" -j "$(nproc)" \
  --target fuzz_protocol fuzz_scene fuzz_protocol_seeds fuzz_scene_seeds
ctest --test-dir "$root/build-fuzz" -L fuzz --output-on-failure -j "$(nproc)" --timeout 1200

cd "$root/build"
ctest --output-on-failure -j "$(nproc)" --timeout 1200 "$@"
