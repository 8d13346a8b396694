#!/usr/bin/env bash
# Renders the same scenes with two builds and compares the images (igi-compare): a change that
# should not touch the image must give relMSE 0 on every line. Usage:
#   scripts/bit_identical.sh BASE_BIN NEW_BIN [--clients N] [--frames N] [--gi MODE] [scene...]
# BASE_BIN and NEW_BIN are folders holding igi-master, igi-client and igi-compare (a build's
# bin/). Without scenes: the default scene and CornellBox-Original, -Glossy, -Mirror, -Sphere
# from ../shared/scenes. Prints one line per scene: its name, relMSE, and both shadow-ray counts.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
base="$1" new="$2"
shift 2
clients=2 frames=4 gi=igi scenes=()
while (($#)); do
  case "$1" in
    --clients) clients="$2"; shift 2 ;;
    --frames) frames="$2"; shift 2 ;;
    --gi) gi="$2"; shift 2 ;;
    *) scenes+=("$1"); shift ;;
  esac
done
if ((${#scenes[@]} == 0)); then
  shared="$root/../shared/scenes/cornell-box"
  scenes=("$root/scenes/cornell/cornell.json" "$shared/CornellBox-Original.obj"
          "$shared/CornellBox-Glossy.obj" "$shared/CornellBox-Mirror.obj"
          "$shared/CornellBox-Sphere.obj")
fi
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
# --allow-outside-paths: the scenes are the caller's own choice, and the Sponza arcades
# (scenes/sponza/arcades.json) read their meshes from ../shared/scenes.
render() {  # BIN SCENE OUT.exr STATS.json
  "$1/igi-master" --scene "$2" --allow-outside-paths --local-clients "$clients" \
    --frames "$frames" --width 320 --height 240 --gi "$gi" --output "$3" --stats-json "$4" \
    --log-level warn >/dev/null
}
shadow() { python3 -c "import json,sys; print(sum(f['shadow_rays'] for f in json.load(open(sys.argv[1]))['frames']))" "$1"; }
for s in "${scenes[@]}"; do
  name="$(basename "$s")"
  render "$base" "$s" "$out/base.exr" "$out/base.json"
  render "$new" "$s" "$out/new.exr" "$out/new.json"
  rel="$("$new/igi-compare" "$out/new.exr" "$out/base.exr" |
    python3 -c "import json,sys; print(json.load(sys.stdin)['relative_mse'])")"
  echo "$name relMSE $rel shadow rays $(shadow "$out/base.json") $(shadow "$out/new.json")"
done
