#!/usr/bin/python3
"""Issue 34's "Must show": glTF PBR materials and Sponza's bump maps against Blender Cycles and our path tracer.

Each scene below is rendered and compared by scripts/lights_mustshow.py's machinery
(render_scene: IGI with --frames accumulated frames, our path tracer at --pt-spp x --pt-frames,
Cycles --cycles-spp with seed 1 and its reference at --ref-spp with seed 2, all through
scripts/peers/cycles_render.py and build/bin/igi-compare), at --width x --height:
  ratio   mean(IGI) / mean(Cycles reference) (target |ratio - 1| <= 2 %);
  bias    mean(IGI) / mean(path) - 1 (target |bias| <= 0.5 %);
  relMSE  IGI's (after --frames frames) and Cycles' --cycles-spp image against the reference
          (target: IGI's <= 1.5 x Cycles' + the diffuse part, below).
The Khronos models of ../shared/scenes/gltf stand in the Cornell room of scenes/cornell, lit by
its ceiling light (scenes/materials/*.json); Dabrovic Sponza with its bump maps is
scenes/sponza/sunlit.json (sun and sky). Cycles reads the glTF files with Blender's own importer
(Principled BSDF set to GGX; alpha MASK applied in the shader, since Blender 3.4 imports it as an
EEVEE-only clip; image alpha channel packed, colours not premultiplied) and Sponza's bump maps
as our height-to-normal rule (cycles_render.py).

Also per scene: IGI again with --seed 2 against the path tracer (how far one run's mean moves),
and for CLOSEUPS a closer camera (IGI 64 frames | Cycles 128 spp | difference, to look at, not a
figure).

The Burley part: scenes/materials/burley-spheres.json (two white dielectric glTF spheres,
roughness 0.35 and 1, scripts/make_white_spheres.py) is also rendered by Cycles with every
Principled's diffuse swapped for a Lambertian Diffuse BSDF (IGI_CYCLES_DIFFUSE=lambert, seed 2,
the reference's spp). relMSE and the mean ratio between the two Cycles references are what
Blender's Burley diffuse alone departs from the glTF specification's Lambert by, on that scene.
Every other glTF scene gets the same Lambert variant (partial where materials are metallic or
textured in alpha or metallic). A second variant (IGI_CYCLES_DIFFUSE=spec) also weights that
Lambertian diffuse by 1 - f0, the specification's 1 - F(v.h) at its largest (Principled weights
its diffuse by nothing): its relMSE to the reference is that scene's diffuse part of the relMSE
target, what Blender's diffuse departs from the specification by, at the least.

Writes under --out (build/materials_mustshow) every render and log (reused when present; --rerun
renders again); under --docs (docs/materials) <scene>.png (IGI | Cycles reference |
difference), results.json and results.csv; and the block between `BEGIN GENERATED
materials-mustshow` and `END GENERATED materials-mustshow` of docs/MATERIALS.md.

Run it through scripts/materials_mustshow.sh. Everything heavy runs under nice -n 19.
"""

import argparse
import copy
import json
import os
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import lights_mustshow as lm  # noqa: E402
from report_util import machine, splice  # noqa: E402

G = "Khronos glTF sample model "
SCENES = [
    {"name": "burley-spheres", "file": "scenes/materials/burley-spheres.json",
     "what": "two white dielectric spheres (roughness 0.35 and 1; scripts/make_white_spheres.py): the Burley scene"},
    {"name": "metal-rough-spheres", "file": "scenes/materials/metal-rough-spheres.json",
     "what": G + "MetalRoughSpheresNoTextures (metallic and roughness sweeps)"},
    {"name": "normal-tangent-mirror", "file": "scenes/materials/normal-tangent-mirror.json",
     "what": G + "NormalTangentMirrorTest (normal maps, metallic-roughness texture)"},
    {"name": "alpha-blend-mode", "file": "scenes/materials/alpha-blend-mode.json",
     "what": G + "AlphaBlendModeTest (OPAQUE, MASK at 0.25, 0.5, 0.75, BLEND)"},
    {"name": "texture-transform", "file": "scenes/materials/texture-transform.json",
     "what": G + "TextureTransformTest (KHR_texture_transform)"},
    {"name": "emissive-strength", "file": "scenes/materials/emissive-strength.json",
     "what": G + "EmissiveStrengthTest (KHR_materials_emissive_strength 1 to 16)"},
    {"name": "sponza-bump", "file": "scenes/sponza/sunlit.json",
     "what": "Dabrovic Sponza with its 18 bump maps, sun and sky (scenes/sponza/sunlit.json)", "principled": False},
]
# Not compared (named in the generated block with the reason).
SKIPPED = {
    "LightsPunctualLamp": "its shade is KHR_materials_transmission with a transmissionTexture, which we "
                          "render as clear refracting glass (docs/MATERIALS.md, \"Still approximated\": "
                          "partial transmission is not modelled) and Blender as Principled transmission "
                          "weighted by the texture; and its emissive BLEND cut-outs still emit from their "
                          "whole triangles in ours (\"Alpha\", not modelled). The difference would measure "
                          "those known approximations, not the materials this block is about.",
}
KEY = "materials-mustshow"
# Images this small are drawn at 4x (lights_mustshow's side_by_side, after render_scene's 2x).
ZOOM = 4
# A closer look where the figures miss: the scene with another camera, IGI 64 frames against
# Cycles 128 spp, at 160 x 120 (what each shows, not a measurement).
CLOSEUPS = {
    "texture-transform": {"position": [0, 0.9, 1.15], "look_at": [0, 0.9, -0.6], "up": [0, 1, 0], "fov_y": 40},
    "alpha-blend-mode": {"position": [0, 0.45, 1.9], "look_at": [0, 0.35, 0], "up": [0, 1, 0], "fov_y": 40},
}


def lambert_render(r, tag, scene_file, spp, variant="lambert"):
    """A scene by Cycles with every Principled's diffuse Lambertian ("lambert"), or Lambertian and
    weighted by 1 - f0 ("spec"), seed 2, at the reference's spp."""
    prefix = os.path.join(r.a.out, tag, f"cycles-{variant}")
    os.environ["IGI_CYCLES_DIFFUSE"] = variant
    try:
        meta = r.cycles(os.path.join(ROOT, scene_file), prefix, [spp], 2)
    finally:
        del os.environ["IGI_CYCLES_DIFFUSE"]
    return meta, f"{prefix}-{spp}spp.exr"


def closeup(a, tag, camera):
    """CLOSEUPS[tag]: renders and draws IGI | Cycles | difference to docs/materials/<tag>-closeup.png."""
    scene = json.load(open(os.path.join(ROOT, "scenes", "materials", tag + ".json")))
    scene["camera"] = camera
    out = os.path.join(a.out, tag, "closeup-160")
    os.makedirs(out, exist_ok=True)
    for m in scene["meshes"]:  # --allow-outside-paths takes paths relative to the scene file
        m["file"] = os.path.relpath(os.path.join(ROOT, "scenes", "materials", m["file"]), out)
    path = os.path.join(out, "scene.json")
    with open(path, "w") as f:
        json.dump(scene, f, indent=1)
    b = copy.copy(a)
    b.width, b.height = 160, 120
    r = lm.Runner(b)
    r.master(path, os.path.join(out, "igi.exr"), 64, [])
    r.cycles(path, os.path.join(out, "cycles"), [128], 1)
    if a.docs:
        lm.side_by_side(os.path.join(out, "igi.exr"), os.path.join(out, "cycles-128spp.exr"),
                        os.path.join(a.docs, f"{tag}-closeup.png"), ("IGI, 64 frames", "Cycles, 128 spp"), zoom=2)


def burley(r, tag, scene_file, res):
    """Cycles' reference of a scene against the same with Lambertian diffuse (the Burley part)
    and with Lambertian diffuse weighted by 1 - f0 (the diffuse part: all that Principled's
    diffuse departs from the specification by, at its smallest), and IGI and our path tracer
    against both."""
    out = os.path.join(r.a.out, tag)
    spp = res["ref_spp"]
    meta, lam = lambert_render(r, tag, scene_file, spp)
    smeta, spec = lambert_render(r, tag, scene_file, spp, "spec")
    ps = r.compare(os.path.join(out, f"cycles-ref-{spp}spp.exr"), spec)
    is_ = r.compare(os.path.join(out, "igi.exr"), spec)
    pts = r.compare(os.path.join(out, "path.exr"), spec)
    pb = r.compare(os.path.join(out, f"cycles-ref-{spp}spp.exr"), lam)  # Principled (Burley) against Lambert
    il = r.compare(os.path.join(out, "igi.exr"), lam)
    pl = r.compare(os.path.join(out, "path.exr"), lam)
    b = {"spp": spp, "seconds": meta["renders"][-1]["seconds"],
         "ratio_burley_lambert": 1 + pb["mean_relative_bias"], "relmse_burley_lambert": pb["relative_mse"],
         "ratio_igi_lambert": 1 + il["mean_relative_bias"], "relmse_igi_lambert": il["relative_mse"],
         "ratio_path_lambert": 1 + pl["mean_relative_bias"], "relmse_path_lambert": pl["relative_mse"],
         # Two independent renders of the same spp would carry about twice one reference's noise;
         # these two share seed 2, so much of it is common and cancels (none where the swap
         # changed nothing). The Burley part is therefore the whole relMSE between them: an
         # upper bound, noise that does not cancel included.
         "noise_relmse": 2 * res["ref_noise_relmse"]}
    b.update({"spec_seconds": smeta["renders"][-1]["seconds"],
              "ratio_principled_spec": 1 + ps["mean_relative_bias"], "relmse_principled_spec": ps["relative_mse"],
              "ratio_igi_spec": 1 + is_["mean_relative_bias"], "relmse_igi_spec": is_["relative_mse"],
              "ratio_path_spec": 1 + pts["mean_relative_bias"], "relmse_path_spec": pts["relative_mse"]})
    # The part of the relMSE target: what Principled's diffuse departs from the specification's
    # by (Burley, and no Fresnel weight); the specification's own weight 1 - F(v.h) is at most
    # the variant's 1 - f0, so the departure is larger than this, never smaller.
    b["part"] = b["relmse_principled_spec"]
    lm.log(f"  Burley / Lambert (Cycles) {b['ratio_burley_lambert']:.4f}, relMSE {b['relmse_burley_lambert']:.4g}; "
           f"IGI / Cycles-Lambert {b['ratio_igi_lambert']:.4f}, path / Cycles-Lambert {b['ratio_path_lambert']:.4f}")
    lm.log(f"  Principled / spec diffuse (Cycles) {b['ratio_principled_spec']:.4f}, relMSE "
           f"{b['relmse_principled_spec']:.4g}; IGI / Cycles-spec {b['ratio_igi_spec']:.4f} (relMSE "
           f"{b['relmse_igi_spec']:.4g}), path / Cycles-spec {b['ratio_path_spec']:.4f}")
    return b


def variant_rows(results, cells):
    """A table row per scene with Cycles variants (burley's figures): `cells(figures)` after its name."""
    return [f"| {tag} | " + " | ".join(cells(r["lambert"])) + " |" for tag, r in results.items() if r.get("lambert")]


def markdown(results, a, command, started, seconds):
    pct = lm.pct
    m = machine()
    lines = [
        f"Generated by `{command}` on {m['cpu']} ({m['nproc']} cores, shared with other work; everything "
        f"under `nice -n 19`), started {started}, {seconds / 60:.0f} min for this pass (renders kept in "
        f"`{os.path.relpath(a.out, ROOT)}/` are reused: the times below are each render's own). "
        f"{a.width} x {a.height}, smaller than the issue's images so that every render fits the machine; IGI "
        f"{a.frames} accumulated frames, one local client of {a.threads} threads; our path tracer "
        f"{a.pt_spp} spp x {a.pt_frames} frames; Cycles (Blender 3.4, GGX, not multiscatter) "
        f"{a.cycles_spp} spp with seed 1, its reference with seed 2 at the spp in the table. "
        "Ratios: means over all pixels and channels (`igi-compare`'s `mean_relative_bias` + 1). The "
        "relMSE target is relMSE(IGI) <= 1.5 x relMSE(Cycles 256 spp) + the scene's diffuse part: what "
        "Blender's Principled diffuse departs from the glTF specification's by, measured as the relMSE "
        "between Cycles' reference and the same render with each Principled's diffuse made the "
        "specification's (Lambertian, weighted by 1 - f0: the largest the specification's weight "
        "1 - F(v.h) can be, so the departure is at least this), both seed 2, the noise that does not "
        "cancel between them included; the tables after this one, which also give Burley alone).", "",
        "| scene | IGI / Cycles ref (target within 2 %) | IGI / path - 1 (target within 0.5 %; with "
        "`--seed 2`) | relMSE IGI, "
        "Cycles 256 spp, ratio | diffuse part | relMSE target | path / Cycles ref | relMSE IGI against path | "
        "Cycles ref spp |",
        "|---|---|---|---|---|---|---|---|---|"]
    for tag, r in results.items():
        part = r.get("lambert", {}).get("part", 0.0)
        rel_ok = r["relmse_igi"] <= 1.5 * r["relmse_cycles"] + part
        r["targets"]["relmse_with_burley"] = rel_ok
        lines.append(
            f"| {tag} | {r['ratio_igi_cycles']:.4f} ({lm.ok(r['targets']['ratio'])}) | {pct(r['bias_igi_path'])} "
            f"({lm.ok(r['targets']['bias'])}; {pct(r['bias_igi_path_seed2'])}, "
            f"{lm.ok(abs(r['bias_igi_path_seed2']) <= 0.005)}) | {r['relmse_igi']:.3g}, {r['relmse_cycles']:.3g}, "
            f"{r['relmse_ratio']:.2f} | {part:.2g} | {lm.ok(rel_ok)} | {r['ratio_path_cycles']:.4f} | "
            f"{r['relmse_igi_path']:.3g} | {r['ref_spp']} |")
    lines += ["", "What each scene is: " + "; ".join(f"**{t}**: {next(s['what'] for s in SCENES if s['name'] == t)}"
                                                    for t in results) + ".", "",
              "**Burley against Lambert.** Each glTF scene again by Cycles at its reference's spp (seed 2) "
              "with every Principled BSDF's diffuse swapped for a Diffuse BSDF of roughness 0, its "
              "specular lobes unchanged (`IGI_CYCLES_DIFFUSE=lambert`; only opaque dielectrics with "
              "constant metallic 0 are swapped: metals, partly metallic spheres and materials with an alpha or "
              "metallic texture keep Burley, so on those scenes the swap is partial or nothing). burley-spheres "
              "isolates it: two white dielectric spheres and Lambertian (OBJ) walls, nothing else "
              "differs between the two renders.", "",
              "| scene | Cycles Burley / Lambert | relMSE between them (two independent references' noise) | IGI / Cycles-Lambert | "
              "path / Cycles-Lambert | relMSE IGI against Cycles-Lambert |",
              "|---|---|---|---|---|---|"]
    lines += variant_rows(results, lambda b: [f"{b['ratio_burley_lambert']:.4f}",
                                              f"{b['relmse_burley_lambert']:.3g} ({b['noise_relmse']:.2g})",
                                              f"{b['ratio_igi_lambert']:.4f}", f"{b['ratio_path_lambert']:.4f}",
                                              f"{b['relmse_igi_lambert']:.3g}"])
    lines += ["", "**Blender's diffuse against the specification's.** Principled (Blender 3.x) adds its "
              "specular lobe on top of an unweighted Burley diffuse; the specification weights a Lambertian "
              "diffuse by 1 - F(v.h) (ours by the constant 1 - f0: \"Where it departs from the "
              "specification\" above). The same scenes again with the Lambert variant's diffuse also "
              "times 1 - f0 (`IGI_CYCLES_DIFFUSE=spec`, f0 = 0.08 x Principled's Specular, 0.04 as "
              "imported): its relMSE to the reference is the diffuse part of the target above.", "",
              "| scene | Cycles Principled / spec diffuse | relMSE between them (the diffuse part) | IGI / Cycles-spec | "
              "path / Cycles-spec | relMSE IGI against Cycles-spec | relMSE path against Cycles-spec |",
              "|---|---|---|---|---|---|---|"]
    lines += variant_rows(results, lambda b: [f"{b['ratio_principled_spec']:.4f}", f"{b['relmse_principled_spec']:.3g}",
                                              f"{b['ratio_igi_spec']:.4f}", f"{b['ratio_path_spec']:.4f}",
                                              f"{b['relmse_igi_spec']:.3g}", f"{b['relmse_path_spec']:.3g}"])
    lines += ["", "Not compared: " + "; ".join(f"**{k}**: {v}" for k, v in SKIPPED.items()), "",
              "Time (seconds of rendering as each renderer reports it, wall clock on the shared machine):", "",
              "| scene | IGI (frames) | our path tracer (spp) | Cycles 256 spp | Cycles reference | Cycles Lambert variant | Cycles spec variant |",
              "|---|---|---|---|---|---|---|"]
    for tag, r in results.items():
        lam = f"{r['lambert']['seconds']:.1f}" if r.get("lambert") else "-"
        spec = f"{r['lambert']['spec_seconds']:.1f}" if r.get("lambert") else "-"
        lines.append(f"| {tag} | {r['igi_seconds']:.1f} ({r['igi_frames']}) | {r['path_seconds']:.1f} "
                     f"({r['path_spp']}) | {r['cycles_seconds']:.1f} | {r['ref_seconds']:.1f} | {lam} | {spec} |")
    lines += ["", "The reference's own noise, about relMSE(Cycles 256) x 256 / ref spp, is in both relMSE "
              "figures: " + ", ".join(f"{t} {r['ref_noise_relmse']:.2g}" for t, r in results.items()) + ".", ""]
    for tag in results:
        lines += [f"![{tag}: IGI, Cycles and their difference](materials/{tag}.png)", ""]
        if tag in CLOSEUPS:
            lines += [f"![{tag}, closer (160 x 120; IGI 64 frames, Cycles 128 spp)](materials/{tag}-closeup.png)", ""]
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    lm.common_args(ap, "materials", SCENES, 80, 60, 2048)
    a = lm.parse(ap)
    a.seconds, a.cycles_max_spp = 0, a.ref_spp  # no relMSE-against-time curve here
    started, t0 = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), time.time()
    r = lm.Runner(a)
    wanted = a.scenes.split(",")
    results, rows = {}, []
    for sc in SCENES:
        if sc["name"] not in wanted:
            continue
        res = lm.render_scene(r, sc, os.path.join(ROOT, sc["file"]), sc["name"], False, results, rows)
        res["what"] = sc["what"]
        if a.docs and not a.cycles_only:
            out = os.path.join(a.out, sc["name"])
            lm.side_by_side(os.path.join(out, "igi.exr"), os.path.join(out, f"cycles-ref-{res['ref_spp']}spp.exr"),
                            os.path.join(a.docs, f"{sc['name']}.png"),
                            (f"IGI, {a.frames} frames", f"Cycles, {res['ref_spp']} spp"), zoom=ZOOM)
        if not a.cycles_only:
            # The bias again with another IGI seed: how far one run's mean moves.
            out = os.path.join(a.out, sc["name"])
            r.master(os.path.join(ROOT, sc["file"]), os.path.join(out, "igi-seed2.exr"), a.frames, ["--seed", "2"])
            res["bias_igi_path_seed2"] = r.compare(os.path.join(out, "igi-seed2.exr"),
                                                   os.path.join(out, "path.exr"))["mean_relative_bias"]
        if sc["name"] in CLOSEUPS and not a.cycles_only:
            closeup(a, sc["name"], CLOSEUPS[sc["name"]])
        if sc.get("principled", True):
            if a.cycles_only:
                lambert_render(r, sc["name"], sc["file"], res["ref_spp"])
                lambert_render(r, sc["name"], sc["file"], res["ref_spp"], "spec")
            else:
                res["lambert"] = burley(r, sc["name"], sc["file"], res)
        if not a.cycles_only and a.docs:
            write_docs(a, r, results, rows, started, t0)  # after every scene: a partial run leaves what it has
    if a.cycles_only:
        return
    for tag, x in results.items():
        print(f"{tag:22s} IGI/Cycles {x['ratio_igi_cycles']:.4f}  IGI/path-1 {x['bias_igi_path']:+.4f}  "
              f"relMSE IGI {x['relmse_igi']:.3g} Cycles256 {x['relmse_cycles']:.3g} ({x['relmse_ratio']:.2f}x)  "
              f"path/Cycles {x['ratio_path_cycles']:.4f}")
    print(f"total {(time.time() - t0) / 60:.1f} min")


def write_docs(a, r, results, rows, started, t0):
    lm.write_results(a.docs, {"scenes": results, "skipped": SKIPPED}, rows)
    command = "scripts/materials_mustshow.sh" + (" " + " ".join(sys.argv[1:]) if sys.argv[1:] else "")
    splice(os.path.join(ROOT, "docs", "MATERIALS.md"),
           {KEY: markdown(results, a, command, started, time.time() - t0)}, lm.log)


if __name__ == "__main__":
    main()
