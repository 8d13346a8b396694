#!/usr/bin/env bash
# Our spot, directional and environment lights against Blender Cycles (an independent renderer)
# and against our own path tracer (the exact reference of our model), at 160 x 120.
#
# For each scene (scenes/cornell/sunlit.json, scenes/sky/sky.json) it renders the scene as it is
# and one copy per light source (each light alone, the environment alone), with
#   Cycles:   scripts/peers/cycles_render.py, $SPP samples per pixel
#   IGI:      igi-master, $FRAMES accumulated frames
#   path:     igi-master --integrator path, $PT_SPP spp per frame x $FRAMES frames
# and prints the mean ratio (mean over all pixels and channels of one image over the other's:
# igi-compare's mean_relative_bias + 1) and relMSE of each pair.
#
# Installs Blender (apt-get) only if it is missing; builds igi-master, igi-client and igi-compare
# in build/ unless SKIP_BUILD=1. Renders already in $OUT are reused (RERUN=1 renders them again).
# Everything heavy runs under nice -n 19.
#
# Usage: scripts/lights_cycles.sh            (SPP=1024 FRAMES=256 PT_SPP=16 THREADS=2 OUT=build/lights_cycles)
#        ONLY_FULL=1 scripts/lights_cycles.sh   (whole scenes only, no per-light copies)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
W=${W:-160}
H=${H:-120}
SPP=${SPP:-1024}
FRAMES=${FRAMES:-256}
PT_SPP=${PT_SPP:-16}
THREADS=${THREADS:-2}
OUT=${OUT:-$root/build/lights_cycles}
SCENES=${SCENES:-"cornell/sunlit sky/sky"}
bin=${BIN:-$root/build/bin}  # BIN: binaries built elsewhere from the same sources
# Cycles' spot falloff: ours (the default, a light shader with the glTF ramp) or "cycles"
# (Cycles' own smoothstep blend); scripts/peers/cycles_render.py reads it.
export IGI_CYCLES_SPOT_RAMP=${IGI_CYCLES_SPOT_RAMP:-ours}

if ! command -v blender >/dev/null; then
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  $sudo apt-get update
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y blender
fi
if [ "${SKIP_BUILD:-0}" != 1 ]; then
  nice -n 19 cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release >/dev/null
  nice -n 19 cmake --build "$root/build" -j2 --target igi-master igi-client igi-compare
fi
mkdir -p "$OUT"
blender --version | head -n 1

# Copies of each scene's folder (clients read only paths inside the scene's folder) with one
# scene file per light source beside the original.
variants=()
for s in $SCENES; do
  dir=$(dirname "$s")
  name=$(basename "$s")
  mkdir -p "$OUT/scenes"
  mkdir -p "$OUT/scenes/$dir"
  cp -r "$root/scenes/$dir/." "$OUT/scenes/$dir/"
  variants+=("$OUT/scenes/$dir/$name.json")
  if [ "${ONLY_FULL:-0}" != 1 ]; then
    while read -r v; do variants+=("$v"); done < <(python3 "$root/scripts/light_variants.py" \
      "$OUT/scenes/$dir/$name.json")
  fi
done

render() {  # what, output, command...
  local out=$2
  shift 2
  if [ -s "$out" ] && [ "${RERUN:-0}" != 1 ]; then return; fi
  echo "rendering $out" >&2
  "$@" >"${out%.exr}.log" 2>&1 || { tail -n 20 "${out%.exr}.log" >&2; exit 1; }
}

rows="$OUT/table.tsv"
: >"$rows"
for scene in "${variants[@]}"; do
  tag=$(basename "${scene%.json}")
  o="$OUT/$tag"
  render cycles "$o.cycles-${SPP}spp.exr" nice -n 19 blender -b --factory-startup -noaudio \
    -P "$root/scripts/peers/cycles_render.py" -- "$scene" "$o.cycles" "$W" "$H" "$THREADS" "$SPP"
  render igi "$o.igi.exr" nice -n 19 "$bin/igi-master" --scene "$scene" --local-clients 1 \
    --frames "$FRAMES" --width "$W" --height "$H" --output "$o.igi.exr" --listen 127.0.0.1:0
  render path "$o.path.exr" nice -n 19 "$bin/igi-master" --scene "$scene" --local-clients 1 \
    --integrator path --spp "$PT_SPP" --frames "$FRAMES" --width "$W" --height "$H" \
    --output "$o.path.exr" --listen 127.0.0.1:0
  for pair in "igi cycles-${SPP}spp" "path cycles-${SPP}spp" "igi path"; do
    set -- $pair
    "$bin/igi-compare" "$o.$1.exr" "$o.$2.exr" >"$o.$1-vs-$2.json"
    python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); print("\t".join([sys.argv[2], sys.argv[3], sys.argv[4], "%.4f" % (1 + d["mean_relative_bias"]), "%.4g" % d["relative_mse"], "%.3f" % d["ssim"]]))' \
      "$o.$1-vs-$2.json" "$tag" "$1" "${2%-*spp}" >>"$rows"
  done
done

echo
echo "160x120: Cycles $SPP spp, IGI $FRAMES frames, path tracer $((PT_SPP * FRAMES)) spp; ratio = mean(image) / mean(reference)"
printf '%-28s %-6s %-8s %8s %10s %6s\n' scene image reference ratio relMSE SSIM
while IFS=$'\t' read -r tag a b ratio rel ssim; do
  printf '%-28s %-6s %-8s %8s %10s %6s\n' "$tag" "$a" "$b" "$ratio" "$rel" "$ssim"
done <"$rows"
