#!/usr/bin/env bash
# Issue 35, item 6 (docs/LIGHTS.md, "Every GI mode"): every GI mode and the path tracer take the
# sun, spot and environment lights through the same code. Renders each scene with each mode
# (`--gi`, light sampling by the tree so that every mode samples lights alike) and with the
# path tracer, and prints each one's mean relative bias and relMSE against `igi`, the mode the
# must-show measures against Cycles (docs/LIGHTS.md, "Must show").
#
# Usage: scripts/lights_modes.sh [BIN] [OUT] [scene...]   (BIN: where igi-master and igi-compare
# are, default build/bin; OUT: default build/lights_modes; scenes: default scenes/sky/sky.json,
# scenes/cornell/sunlit.json and scenes/cornell/spot.json). Renders in OUT are reused.
# Environment: W, H (160 x 120), FRAMES (8, accumulated), MODES ("igi spt stream cache
# photonmap"), SPP (the path tracer's spp per frame, 64; it renders FRAMES frames).
#
# Eight frames are noisy: the figures say whether a mode lost or doubled a light (tens of per
# cent), not whether it agrees to a tenth of a per cent. sunlit.json's sun reaches the floor
# through the mirror box and the glass ball, light the path tracer does not find (docs/LIGHTS.md,
# "Against Blender Cycles"): its row says so.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BIN=${1:-$ROOT/build/bin}
OUT=${2:-$ROOT/build/lights_modes}
shift $(($# > 2 ? 2 : $#))
SCENES=("$@")
[ ${#SCENES[@]} -gt 0 ] ||
    SCENES=("$ROOT/scenes/sky/sky.json" "$ROOT/scenes/cornell/sunlit.json" "$ROOT/scenes/cornell/spot.json")
W=${W:-160} H=${H:-120} FRAMES=${FRAMES:-8} SPP=${SPP:-64}
MODES=${MODES:-"igi spt stream cache photonmap"}
mkdir -p "$OUT"
. "$ROOT/scripts/render_small.sh"

compare() {  # image reference -> "bias relMSE"
    "$BIN/igi-compare" "$1" "$2" | /usr/bin/python3 -c \
        'import json, sys; d = json.load(sys.stdin); print("%+.2f %% %.3g" % (100 * d["mean_relative_bias"], d["relative_mse"]))'
}

printf '%-14s %-10s %-10s %s\n' scene mode "bias" "relMSE (against igi)"
for scene in "${SCENES[@]}"; do
    name=$(basename "${scene%.json}")
    for mode in $MODES; do
        render "$scene" "$OUT/$name-$mode.exr" "$FRAMES" --gi "$mode" --light-sampling tree
    done
    render "$scene" "$OUT/$name-path.exr" "$FRAMES" --integrator path --spp "$SPP"
    for mode in $MODES path; do
        [ "$mode" = igi ] && continue
        read -r bias unit rel < <(compare "$OUT/$name-$mode.exr" "$OUT/$name-igi.exr")
        printf '%-14s %-10s %-10s %s\n' "$name" "$mode" "$bias $unit" "$rel"
    done
done
