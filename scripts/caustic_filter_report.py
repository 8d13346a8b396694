#!/usr/bin/python3
"""Larsen and Christensen's screen-space caustic filter against IGI's hashed-grid gather
(docs/MODES.md, "Simulated photon mapping": the caustic filter), on the shared CornellBox-Sphere
and CornellBox-Water.

Per scene:
  1. a reference from our path tracer (--ref-spp x --ref-frames spp; cached in --out);
  2. the caustic region: the pixels where IGI's caustics are (IGI accumulated for 64 frames with
     --caustic-photons 8000 against the same session with none: 3 x 3 blurred luminance higher
     by more than 5 % of the pixel plus 1 % of the image mean);
  3. `--gi photonmap` with `--photonmap-caustics screen` (the paper's filter) and `grid` (IGI's
     gather), each --frames frames with --no-accumulate, every frame kept: what a user sees while
     things move, which is where the filter is meant to help. The same seeds, the same photons;
     only the filter differs, so the time per frame is nearly equal, and the table gives it;
  4. per frame, relMSE (as igi-compare computes it) in the caustic region and over the image; the
     means over the frames and seeds.

Writes --docs (caustic-filter.md and .json) and the block "caustic-filter" of docs/MODES.md.
Python 3 with numpy (Debian's python3-numpy, /usr/bin/python3) and oiiotool.
"""

import argparse
import json
import os
import statistics
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import report_util  # noqa: E402
from modes_report import blur3, read_exr  # noqa: E402
from report_util import machine, run  # noqa: E402

SHARED = "/work/shared/scenes/cornell-box"
SCENES = [("cornell-sphere", "CornellBox-Sphere.obj"), ("cornell-water", "CornellBox-Water.obj")]
CAMERA = {"position": [0, 1, 3.9], "look_at": [0, 1, 0], "up": [0, 1, 0], "fov_y": 40}
VARIANTS = [("screen", ["--gi", "photonmap", "--photonmap-caustics", "screen"]),
            ("grid", ["--gi", "photonmap", "--photonmap-caustics", "grid"]),
            ("igi", [])]
REL, ABS = 0.05, 0.01  # caustic region: IGI's caustics add more than REL of the pixel + ABS of the mean


def log(msg):
    import time
    print(f"[caustic-filter {time.strftime('%H:%M:%S')}] {msg}", flush=True)


class Run:
    def __init__(self, a):
        self.a = a
        self.bin = os.path.join(a.build, "bin")
        os.makedirs(a.out, exist_ok=True)

    def scene_file(self, name, obj):
        path = os.path.join(self.a.out, name + ".json")
        with open(path, "w", encoding="utf-8") as f:
            # Relative: a scene bundle holds paths relative to its scene file.
            json.dump({"camera": CAMERA, "meshes": [{"file": os.path.relpath(os.path.join(SHARED, obj), self.a.out)}]},
                      f, indent=1)
        return path

    def master(self, scene, extra, out, frames, sequence=None):
        a = self.a
        stats = out.replace(".exr", "-stats.json")
        cmd = [os.path.join(self.bin, "igi-master"), "--scene", scene, "--allow-outside-paths",
               "--local-clients", str(a.clients), "--width", str(a.width), "--height", str(a.height),
               "--frames", str(frames), "--output", out, "--stats-json", stats, "--log-level", "error", *extra]
        if sequence:
            cmd += ["--output-sequence", sequence]
        run(cmd)
        with open(stats, encoding="utf-8") as f:
            s = json.load(f)
        return s["seconds"] / len(s["frames"])

    def reference(self, name, scene):
        a = self.a
        path = os.path.join(a.out, f"{name}-ref-{a.width}x{a.height}-{a.ref_spp * a.ref_frames}spp.exr")
        if not os.path.exists(path):
            log(f"{name}: reference, path tracer {a.ref_spp} spp x {a.ref_frames} frames")
            self.master(scene, ["--integrator", "path", "--spp", str(a.ref_spp)], path, a.ref_frames)
        return read_exr(path, a.out)

    def region(self, name, scene):
        with_c = os.path.join(self.a.out, f"{name}-igi-caustics.exr")
        without = os.path.join(self.a.out, f"{name}-igi-none.exr")
        self.master(scene, ["--caustic-photons", "8000"], with_c, 64)
        self.master(scene, ["--caustic-photons", "0"], without, 64)
        lum = lambda img: img @ np.array([0.2126, 0.7152, 0.0722])  # noqa: E731
        a, b = blur3(lum(read_exr(with_c, self.a.out))), blur3(lum(read_exr(without, self.a.out)))
        return (a - b) > REL * b + ABS * float(a.mean())


def relmse(img, ref, mask=None):
    d = (img.astype(np.float64) - ref) ** 2 / (ref.astype(np.float64) ** 2 + 0.01)
    return float(d[mask].mean() if mask is not None else d.mean())


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    p.add_argument("--out", default=os.path.join(ROOT, "out", "caustic-filter"))
    p.add_argument("--docs", default=os.path.join(ROOT, "docs", "modes"))
    p.add_argument("--doc", default=os.path.join(ROOT, "docs", "MODES.md"))
    p.add_argument("--width", type=int, default=320)
    p.add_argument("--height", type=int, default=240)
    p.add_argument("--clients", type=int, default=2)
    p.add_argument("--frames", type=int, default=16, help="frames per session, each judged alone")
    p.add_argument("--seeds", default="1,2", help="sessions per variant")
    p.add_argument("--ref-spp", type=int, default=64)
    p.add_argument("--ref-frames", type=int, default=64)
    p.add_argument("--command", default="scripts/caustic_filter_report.py")
    a = p.parse_args()
    seeds = [int(s) for s in a.seeds.split(",") if s]
    r = Run(a)
    started = machine()
    results = {}
    for name, obj in SCENES:
        scene = r.scene_file(name, obj)
        ref = r.reference(name, scene)
        mask = r.region(name, scene)
        log(f"{name}: caustic region {mask.mean() * 100:.2f} % of the pixels")
        results[name] = {"region_fraction": float(mask.mean()), "variants": {}}
        for variant, extra in VARIANTS:
            spf, region, whole = [], [], []
            for seed in seeds:
                pattern = os.path.join(a.out, f"{name}-{variant}-s{seed}-%04d.exr")
                out = os.path.join(a.out, f"{name}-{variant}-s{seed}.exr")
                spf.append(r.master(scene, extra + ["--no-accumulate", "--seed", str(seed)], out, a.frames, pattern))
                for k in range(a.frames):
                    img = read_exr(pattern % k, a.out)
                    region.append(relmse(img, ref, mask))
                    whole.append(relmse(img, ref))
            v = {"spf": statistics.median(spf), "region_relmse": statistics.mean(region),
                 "region_relmse_median": statistics.median(region), "image_relmse": statistics.mean(whole)}
            results[name]["variants"][variant] = v
            log(f"{name} {variant}: {v['spf'] * 1e3:.1f} ms/frame, caustic region relMSE {v['region_relmse']:.4g} "
                f"(median {v['region_relmse_median']:.4g}), image {v['image_relmse']:.4g}")
    end = machine()
    lines = [f"- command: `{a.command}`",
             f"- machine: {end['nproc']} cores ({end['cpu']}); started {started['date']} (load {started['load']}), "
             f"finished {end['date']} (load {end['load']})",
             f"- {a.width} x {a.height}, {a.clients} local clients, {a.frames} frames per session with "
             f"--no-accumulate, seeds {a.seeds}; reference our path tracer at {a.ref_spp * a.ref_frames} spp", "",
             "| scene | caustic region | variant | ms/frame | relMSE in the region: mean (median) | relMSE of the image | region relMSE against the grid's |",
             "|---|---|---|---|---|---|---|"]
    for name, res in results.items():
        grid = res["variants"]["grid"]["region_relmse"]
        for variant, v in res["variants"].items():
            label = {"screen": "`photonmap`, screen-space filter (the paper's)",
                     "grid": "`photonmap`, hashed-grid gather",
                     "igi": "`igi` (hashed-grid gather)"}[variant]
            lines.append(f"| {name} | {res['region_fraction'] * 100:.1f} % of the pixels | {label} | "
                         f"{v['spf'] * 1e3:.1f} | {v['region_relmse']:.4g} ({v['region_relmse_median']:.4g}) | "
                         f"{v['image_relmse']:.4g} | {v['region_relmse'] / grid:.2f} |")
    text = "\n".join(lines)
    os.makedirs(a.docs, exist_ok=True)
    with open(os.path.join(a.docs, "caustic-filter.md"), "w", encoding="utf-8") as f:
        f.write(text + "\n")
    with open(os.path.join(a.docs, "caustic-filter.json"), "w", encoding="utf-8") as f:
        json.dump({"command": a.command, "machine_start": started, "machine_end": end, "results": results}, f,
                  indent=1)
    report_util.splice(a.doc, {"caustic-filter": text}, log)
    print(text)


if __name__ == "__main__":
    main()
