#!/usr/bin/env bash
# glTF lights' units against Blender Cycles (issue 35, item 5): scenes/gltf_lights holds a point,
# a spot and a directional KHR_lights_punctual light in candela and lux (written by
# scripts/make_gltf_lights_scene.py), each over a diffuse OBJ floor. igi reads the glTF files
# itself; Cycles gets them through Blender's own glTF importer in its "Standard" lighting mode
# (scripts/peers/cycles_render.py). The mean ratios igi / Cycles are 1 only if both convert
# the units the same way (cd / 683 = W/sr, lux / 683 = W/m^2); a factor such as 4 pi or 683
# would show at once. The floor seen lies inside the spot's inner cone, so its ramp plays no part.
#
# Usage: scripts/gltf_light_units.sh   (SPP, FRAMES, PT_SPP, OUT as in scripts/lights_cycles.sh;
#        defaults here: SPP=256 FRAMES=64 PT_SPP=4 OUT=build/gltf_light_units)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export SPP=${SPP:-256} FRAMES=${FRAMES:-64} PT_SPP=${PT_SPP:-4}
export OUT=${OUT:-$root/build/gltf_light_units}
export SCENES="gltf_lights/point gltf_lights/spot gltf_lights/sun" ONLY_FULL=1
exec "$root/scripts/lights_cycles.sh"
