#!/usr/bin/env bash
# Renders the cached path-traced reference of the convergence test (client/Convergence_test.cpp):
# the project's default scene at 64 x 48 with our path tracer, 2 x 32768 samples per pixel
# (two halves of different seeds, averaged), into client/testdata/default-64x48-reference.exr,
# with how it was made in default-64x48-reference.json. About 6 minutes on 2 cores. Run it
# again whenever the default scene changes (the test then fails and says so).
# Needs a build (scripts/setup.sh) and oiiotool (openimageio-tools).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bin="${IGI_BUILD:-$root/build}/bin"
out="$root/client/testdata"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
for seed in 1 2; do
  "$bin/igi-master" --scene "$root/scenes/cornell/cornell.json" --local-clients 2 --width 64 \
    --height 48 --integrator path --spp 1024 --frames 32 --max-path-length 64 --seed "$seed" \
    --output "$tmp/half$seed.exr" --log-level warn
done
oiiotool "$tmp/half1.exr" "$tmp/half2.exr" --add --mulc 0.5 -d float \
  -o "$out/default-64x48-reference.exr"
cat >"$out/default-64x48-reference.json" <<JSON
{
  "command": "scripts/make_bias_reference.sh",
  "scene": "scenes/cornell/cornell.json",
  "size": [64, 48],
  "integrator": "path",
  "samples_per_pixel": 65536,
  "seeds": [1, 2]
}
JSON
echo "wrote $out/default-64x48-reference.exr and .json"
