#!/usr/bin/env bash
# Issue 35: which scenes gain from choosing VPLs by importance (`vpl_sampling` importance) rather
# than connecting every VPL of a set (all), at equal frames and at equal time: the scenes lit by
# a sun or an environment map. It decided that `auto` keeps `all` for them and that the sunlit
# Sponza's scene file asks for importance (docs/LIGHTS.md, "VPLs by importance under a sun").
#
# Per scene, in OUT/<scene>/: IGI at 80 x 60, 256 frames, seeds 1 to 4, with each setting; the
# relMSE of each against a reference (mean of the seeds, and the same with each image's worst 1 %
# of pixels left out, which a sun's image seen through glass or in a mirror dominates at this
# size); the client's CPU time a frame with each setting (`igi-bench --threads 1 --accumulated`,
# 320 x 240, 4 frames, 3 runs in alternation, medians). The reference is our path tracer at
# 4096 spp where it can find the light, else the mean of two 4096-frame IGI renders (one per
# setting, seed 99): a path tracer cannot find a sun reflected by a mirror or refracted by
# glass, which lights scenes/cornell/sunlit.json and scenes/sky/sky.json.
#
# Usage: scripts/vpl_sampling_sun.sh [BIN] [OUT]   (BIN: where igi-master is, default build/bin)
# Environment: SCENES (space-separated name=file=reference, default below), SEEDS ("1 2 3 4").
# Renders already in OUT are reused.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BIN=${1:-$ROOT/build/bin}
OUT=${2:-$ROOT/build/vpl_sampling_sun}
SEEDS=${SEEDS:-"1 2 3 4"}
SCENES=${SCENES:-"sponza-sunlit=scenes/sponza/sunlit.json=path
cornell-sunlit=scenes/cornell/sunlit.json=igi
sky=scenes/sky/sky.json=igi
spheres-courtyard=scenes/sky/spheres-courtyard.json=path
spheres-studio=scenes/sky/spheres-studio.json=path"}
W=80 H=60 FRAMES=256
mkdir -p "$OUT"

variant() {  # scene-file out-file setting: a copy of the scene with render.vpl_sampling set
    python3 - "$1" "$2" "$3" <<'PY'
import json, os, sys
scene, out, how = sys.argv[1:]
s = json.load(open(scene))
here = os.path.dirname(os.path.abspath(scene))
for m in s.get("meshes", []) + [s.get("environment", {})]:  # relative to the copy
    if "file" in m:
        m["file"] = os.path.relpath(os.path.join(here, m["file"]), os.path.dirname(os.path.abspath(out)))
s.setdefault("render", {})["vpl_sampling"] = how
json.dump(s, open(out, "w"), indent=1)
PY
}
. "$ROOT/scripts/render_small.sh"
bench() {  # scene: the client's CPU seconds a frame (igi-bench's line)
    nice -n 19 "$BIN/igi-bench" --scene "$1" --allow-outside-paths --threads 1 --accumulated \
        --width 320 --height 240 --frames 4 --segments 100000 2>/dev/null |
        python3 -c 'import json, sys; b = json.load(sys.stdin); print(b["client_cpu_seconds"] / b["client_frames"])'
}

printf '| scene | reference | relMSE all | relMSE importance | ratio | without the worst 1 %%: all | importance | ratio | CPU a frame, importance / all | equal-time gain |\n'
printf '|---|---|---|---|---|---|---|---|---|---|\n'
while read -r spec; do
    [ -n "$spec" ] || continue
    IFS== read -r name file ref <<< "$spec"
    d=$OUT/$name
    mkdir -p "$d"
    for how in all importance; do variant "$ROOT/$file" "$d/$how.json" "$how"; done
    if [ "$ref" = path ]; then
        render "$d/all.json" "$d/ref-path.exr" 16 --integrator path --spp 256
        refs="$d/ref-path.exr"
    else
        render "$d/all.json" "$d/ref-all.exr" 4096 --seed 99
        render "$d/importance.json" "$d/ref-importance.exr" 4096 --seed 99
        refs="$d/ref-all.exr $d/ref-importance.exr"
    fi
    for how in all importance; do
        for seed in $SEEDS; do render "$d/$how.json" "$d/$how-s$seed.exr" "$FRAMES" --seed "$seed"; done
    done
    # The client's CPU a frame, alternating the two settings.
    ta="" ti=""
    for run in 1 2 3; do
        ta="$ta $(bench "$d/all.json")"
        ti="$ti $(bench "$d/importance.json")"
    done
    /usr/bin/python3 - "$d" "$ref" "$SEEDS" "$ta" "$ti" $refs <<'PY'
import statistics, sys
import numpy as np
import OpenImageIO as oiio
d, ref_kind, seeds, ta, ti, *refs = sys.argv[1:]
lum = lambda f: oiio.ImageBuf(f).get_pixels(oiio.FLOAT)[:, :, :3].mean(axis=2)
ref = sum(lum(r) for r in refs) / len(refs)
def errors(img):
    e = np.sort(((img - ref) ** 2 / (ref ** 2 + 1e-2)).ravel())  # igi-compare's relMSE
    return e.mean(), e[: e.size - e.size // 100].mean()
def mean_errors(how):
    e = [errors(lum(f"{d}/{how}-s{s}.exr")) for s in seeds.split()]
    return np.mean([x[0] for x in e]), np.mean([x[1] for x in e])
(a, at), (i, it) = mean_errors("all"), mean_errors("importance")
cost = statistics.median(float(x) for x in ti.split()) / statistics.median(float(x) for x in ta.split())
name = d.rstrip("/").split("/")[-1]
refname = "path tracer, 4096 spp" if ref_kind == "path" else "IGI, 2 x 4096 frames"
print(f"| {name} | {refname} | {a:.3g} | {i:.3g} | {a / i:.2f} | {at:.3g} | {it:.3g} | {at / it:.2f} | {cost:.2f} | "
      f"{at / it / cost:.2f} |")
PY
done <<< "$SCENES"
