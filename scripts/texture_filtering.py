#!/usr/bin/python3
"""Where IGI and Cycles differ at texel edges: Cycles' filtering of 8-bit sRGB textures.

Cycles interpolates an 8-bit sRGB texture's bytes and decodes the result to linear afterwards
(svm_image: color_srgb_to_linear after the lookup); the glTF specification asks for the decode
before the filtering, as we do. Across a sharp edge of texels the sRGB blend is the darker, so a
bright line between dark texels (the frames of TextureTransformTest's squares) comes out thinner
in Cycles: the "outline of difference" of docs/MATERIALS.md's texture-transform close-up.

This renders the close-up with Cycles twice, seed 1, 128 spp: as Blender loads the textures
("bytes") and with each sRGB texture decoded to linear floats before Cycles filters it
(IGI_CYCLES_TEXTURES=linear, scripts/peers/cycles_render.py). The "edge" pixels are those where
the two Cycles images differ by more than --edge (relative): the texel edges, nothing else.
It prints IGI's mean ratio to each on the edge pixels and on the others; if the sRGB filtering is
the cause, IGI against "linear" is on the edges what it is elsewhere.

Needs the close-up that scripts/materials_mustshow.sh renders (its IGI image and scene file, in
build/materials_mustshow/texture-transform/closeup-160/). Usage:
  /usr/bin/python3 scripts/texture_filtering.py [--dir DIR] [--edge 0.03] [--threads 2]
"""
import argparse
import os
import sys

import numpy
import OpenImageIO as oiio

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import lights_mustshow as lm  # noqa: E402


def luminance(path):
    return oiio.ImageBuf(path).get_pixels(oiio.FLOAT)[:, :, :3].mean(axis=2)


def cycles(d, variant, threads):
    """The close-up by Cycles with IGI_CYCLES_TEXTURES=variant (lights_mustshow's Runner, which
    keeps an image already rendered); its EXR's path."""
    prefix = os.path.join(d, f"cycles-textures-{variant}")
    r = lm.Runner(argparse.Namespace(width=160, height=120, threads=threads, rerun=False,
                                     build=os.path.join(ROOT, "build"), out=d))
    os.environ["IGI_CYCLES_TEXTURES"] = variant
    try:
        r.cycles(os.path.join(d, "scene.json"), prefix, [128], 1)
    finally:
        del os.environ["IGI_CYCLES_TEXTURES"]
    return prefix + "-128spp.exr"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--dir", default=os.path.join(ROOT, "build", "materials_mustshow", "texture-transform",
                                                  "closeup-160"))
    ap.add_argument("--edge", type=float, default=0.03,
                    help="relative difference between the two Cycles images that makes a pixel an edge")
    ap.add_argument("--threads", type=int, default=2)
    a = ap.parse_args()
    igi_path = os.path.join(a.dir, "igi.exr")
    if not os.path.exists(igi_path) or not os.path.exists(os.path.join(a.dir, "scene.json")):
        sys.exit(f"texture_filtering: {a.dir} has no igi.exr and scene.json: run scripts/materials_mustshow.sh "
                 "--scenes texture-transform first")
    igi = luminance(igi_path)
    by_bytes = luminance(cycles(a.dir, "bytes", a.threads))
    by_linear = luminance(cycles(a.dir, "linear", a.threads))
    lit = (by_bytes > 1e-3) & (by_linear > 1e-3)
    edge = lit & (numpy.abs(by_linear / numpy.maximum(by_bytes, 1e-6) - 1) > a.edge)
    rest = lit & ~edge
    print(f"close-up {igi.shape[1]} x {igi.shape[0]}: {int(edge.sum())} edge pixels "
          f"(Cycles linear against bytes beyond {a.edge:.0%}), {int(rest.sum())} others")
    print("| pixels | Cycles linear / bytes | IGI / Cycles bytes | IGI / Cycles linear |")
    print("|---|---|---|---|")
    for name, m in (("edges", edge), ("others", rest)):
        print(f"| {name} | {by_linear[m].sum() / by_bytes[m].sum():.4f} | {igi[m].sum() / by_bytes[m].sum():.4f} | "
              f"{igi[m].sum() / by_linear[m].sum():.4f} |")


if __name__ == "__main__":
    main()
