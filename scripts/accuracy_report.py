#!/usr/bin/python3
"""Speed against accuracy of igi, convergence, and the peer comparison (docs/ACCURACY.md).

Run through scripts/bench_accuracy.sh (which installs and builds first). Steps, per scene:
  1. a converged reference from our path tracer (>= 4096 spp in the full run: two halves with
     seeds 1 and 2, averaged), cached in --ref (reused when present; the cache key holds the
     size, the sample counts and a hash of the scene file);
  2. unless --no-sweeps, igi parameter sweeps on the three original scenes (indirect VPLs,
     light samples, caustic photons, interleaving + filter), one frame each;
  3. convergence: accumulation long enough for --seconds (60) of render time (at least
     --min-frames, 256): igi at default settings, igi with --converge off (the paper's
     estimator), our path tracer at 1 spp per frame, and with --baseline-build the previous
     build's igi; seconds per frame are measured first by a short run, then only the frames
     needed (1, 2, 4, ..., N) are written (igi-master --sequence-frames);
  4. with --peers, Blender Cycles at doubling sample counts until a render passes --seconds
     (and a probe of Embree's pathtracer);
  5. with --baseline-build, the first frame (relMSE and seconds per frame) of the new and the
     previous build at the same settings, alternated and repeated;
  6. every image against its scene's reference with igi-compare (relMSE, SSIM, bias, speckle);
  7. results.csv, results.md, summary.json and one log-log plot per scene in --docs; the
     blocks between "<!-- BEGIN GENERATED ... -->" markers of docs/ACCURACY.md are replaced,
     the prose around them is kept; a summary of which claims hold is printed at the end.

--modes cache,photonmap is a run of its own (docs/ACCURACY.md, "GI modes"): per scene the
reference, then the accumulation curves of igi and of each named GI mode (igi-master --gi M) and
of our path tracer, for --seconds, and Cycles' points from the main run's results.csv at the same
size (--peer-rows) for the Pareto front. It writes docs/accuracy/modes-WxH/ and replaces only the
block "modes-WxH" of docs/ACCURACY.md, so runs at several sizes sit side by side.

Timing: "s/frame" is the session's render time (first frame opened to last composited, from
--stats-json) over the frames rendered; frames are pipelined, so this is throughput, not the
latency of one frame. An accumulated image of k frames costs k times that ("time"). "wall" is
the whole process, start-up of the local clients and scene shipping included.

Python 3 standard library plus matplotlib (Debian's python3-matplotlib, /usr/bin/python3).
"""

import argparse
import csv
import hashlib
import json
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import threading
import time
from typing import NamedTuple, Optional

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PEERS = os.path.join(ROOT, "scripts", "peers")
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, PEERS)
import embree_scene  # noqa: E402
import igi_scene  # noqa: E402

import report_util
from report_util import machine, num, run


SHARED = "/work/shared/scenes/cornell-box"


class SceneSpec(NamedTuple):
    name: str
    path: str
    specular: bool  # mirrors or glass: the caustic photon sweep matters
    sweeps: bool  # the parameter sweeps run here (unless --no-sweeps)
    cycles: bool  # sent to Blender Cycles (--peers): Cycles can render its materials
    cycles_match: bool  # all materials match Cycles' exactly (diffuse only): Cycles-reference bias judged
    probe: bool  # Embree pathtracer probe (--peers)
    baseline_skip: str = ""  # why the --baseline-build cannot render it ("" = it can)
    materials: Optional[dict] = None  # "materials" of the generated scene file (OBJs only)
    speckle: bool = False  # a speckle claim is judged on it: speckle over several seeds
    # The reference's frames are --ref-frames times this: our path tracer finds the default
    # scene's caustics (a small light through a glass ball) by chance, and at 16384 spp its noise
    # floor is of the order of igi's error after 256 frames, which the slope claim subtracts.
    ref_factor: int = 1


SCENES = [
    SceneSpec("default", os.path.join(ROOT, "scenes/cornell/cornell.json"), True, True, True, False, True,
              ref_factor=4),
    SceneSpec("cornell-original", os.path.join(SHARED, "CornellBox-Original.obj"), False, True, True, True, True),
    SceneSpec("cornell-sphere", os.path.join(SHARED, "CornellBox-Sphere.obj"), True, True, True, False, True),
    # Its MTL lacks the `light` material the OBJ uses: the generated scene file gives it (as
    # common/scene/testdata/cornell-glossy.json does). Cycles cannot do our Phong lobe.
    SceneSpec("cornell-glossy", os.path.join(SHARED, "CornellBox-Glossy.obj"), False, False, False, False, False,
              baseline_skip="the previous build's OBJ loader refuses the material 'light' its MTL lacks",
              materials={"light": {"diffuse": [0.78, 0.78, 0.78], "emission": [17, 12, 4]}}, speckle=True),
    SceneSpec("interior-glossy", os.path.join(ROOT, "scenes/interior/glossy.json"), False, False, False, False, False,
              speckle=True),
    SceneSpec("interior-diffuse", os.path.join(ROOT, "scenes/interior/diffuse.json"), False, False, True, True, False,
              speckle=True),
]
SCENE_NAMES = [s.name for s in SCENES]
# The shared Cornell boxes are bare OBJs; they get a scene file with this explicit camera so that
# every renderer sees the same view (the auto-framing camera would do too, but is less standard).
OBJ_CAMERA = {"position": [0, 1, 3.9], "look_at": [0, 1, 0], "up": [0, 1, 0], "fov_y": 40}

# The claims the convergence part checks (docs/ACCURACY.md, "Convergence").
BIAS_LIMIT = 0.005  # |bias| after BIAS_FRAMES accumulated frames
BIAS_FRAMES = 256
SLOPE_FROM, SLOPE_TO, SLOPE_LIMIT = 16, 256, -0.7  # log-log slope of relMSE against frames
SPECKLE_FRAMES = (1, 32)
# The seed of our path tracer's accumulation curve. Not 1 or 2, the references' halves: the
# path tracer's k-th sample of a pixel depends on the seed and k alone, so with seed 1 its
# 1-spp frames 0 .. 2047 were the first half of a 4096-spp reference, sample for sample, and
# its error fell to the reference's noise floor there (a 16384-spp reference hid the same
# correlation in part).
PATH_SEED = 3
SPECKLE_SEEDS = {1: 12, 32: 4}  # sessions (seeds 1..n) whose mean speckle the claims are judged on
FIRST_FRAME_LIMIT = 1.10  # new / previous build, relMSE and seconds per frame
FIRST_FRAME_SCENES = ("default", "cornell-original", "cornell-sphere")


def log(msg):
    print(f"[accuracy {time.strftime('%H:%M:%S')}] {msg}", flush=True)


def add_bench_arguments(p, name, doc, csv_name, ref_frames, scenes=""):
    """The options of the per-scene reports that compare sessions with the cached references
    (error_estimate_report, adaptive_tiles_report, light_edges_report): where they write, the
    scenes, the image, the sessions and the references' samples."""
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    p.add_argument("--out", default=os.path.join(ROOT, "out", name))
    p.add_argument("--ref", default=os.path.join(ROOT, "out", "reference"), help="cached references (not in git)")
    p.add_argument("--doc", default=os.path.join(ROOT, "docs", doc))
    p.add_argument("--csv", default=os.path.join(ROOT, "docs", "accuracy", csv_name))
    p.add_argument("--scenes", default=scenes, help="comma-separated subset of: " + ", ".join(SCENE_NAMES))
    p.add_argument("--width", type=int, default=160)
    p.add_argument("--height", type=int, default=120)
    p.add_argument("--clients", type=int, default=2)
    p.add_argument("--frames", type=int, default=256)
    p.add_argument("--seed", type=int, default=3, help="igi's session seed (the references use 1 and 2)")
    p.add_argument("--ref-spp", type=int, default=64)
    p.add_argument("--ref-frames", type=int, default=ref_frames,
                   help=f"both halves together (default {64 * ref_frames} spp; the default scene's reference 4 "
                        "times that)")


def bench_for(a):
    """The Bench that renders, caches and compares the references, for add_bench_arguments'
    options (a.build made absolute)."""
    a.build = os.path.abspath(a.build)
    return Bench(argparse.Namespace(build=a.build, baseline_bin="", out=a.out, ref=a.ref, clients=a.clients,
                                    width=a.width, height=a.height, ref_spp=a.ref_spp, ref_frames=a.ref_frames))


def frame_counts(n, start=1):
    """start, 2 start, 4 start, ... below n, and n: the accumulated images the curves keep."""
    ks, k = [], start
    while k < n:
        ks.append(k)
        k *= 2
    ks.append(n)
    return ks


class SequencePruner(threading.Thread):
    """Deletes the frames of an --output-sequence that are not wanted, while the session runs:
    for a master without --sequence-frames (the baseline build), which writes every frame."""

    def __init__(self, pattern, keep):
        super().__init__(daemon=True)
        self.folder, base = os.path.split(pattern)
        prefix, suffix = base.split("%04d")
        self.rx = re.compile(re.escape(prefix) + r"(\d+)" + re.escape(suffix) + "$")
        self.keep = set(keep)
        self.stop = threading.Event()

    def sweep(self, final=False):
        found = []
        for n in os.listdir(self.folder):
            m = self.rx.match(n)
            if m:
                found.append((int(m.group(1)), n))
        if not found:
            return
        top = max(i for i, _ in found)
        for i, n in found:
            # The newest file may still be being written: left to the next sweep.
            if i not in self.keep and (final or i < top):
                try:
                    os.remove(os.path.join(self.folder, n))
                except OSError:
                    pass

    def run(self):
        while not self.stop.wait(0.5):
            self.sweep()

    def finish(self):
        self.stop.set()
        self.join()
        self.sweep(final=True)


def clear_sequence(pattern):
    folder, base = os.path.split(pattern)
    prefix, suffix = base.split("%04d")
    rx = re.compile(re.escape(prefix) + r"\d+" + re.escape(suffix) + "$")
    if os.path.isdir(folder):
        for n in os.listdir(folder):
            if rx.match(n):
                os.remove(os.path.join(folder, n))


class Bench:
    def __init__(self, args):
        self.args = args
        self.bin = os.path.join(args.build, "bin")
        self.base_bin = args.baseline_bin
        self.work = args.out
        self.rows = []
        self.images = {}  # (scene, renderer, frames or spp) -> image path
        self.curves = {}  # scene -> renderer -> {"n", "spf", "spf_estimate"}
        self.first = {}  # scene -> first-frame comparison with the baseline build
        self.cycles_bias = {}  # scene -> IGI's accumulated image against Cycles' best render
        self.speckle = {}  # scene -> frames -> speckle over several seeds (speckle_seeds)
        self.alone_rows = {}  # scene -> renderer -> frames without accumulation (--modes)
        self.notes = []
        self.refs = {}
        self.probes = []
        os.makedirs(self.work, exist_ok=True)
        os.makedirs(args.ref, exist_ok=True)

    # ---------------------------------------------------------------- scenes and references
    def scene_file(self, spec):
        """A scene file usable by igi-master with the benchmark's camera."""
        if not spec.path.lower().endswith(".obj"):
            return spec.path, []
        folder = os.path.join(self.work, "scenes")
        os.makedirs(folder, exist_ok=True)
        out = os.path.join(folder, spec.name + ".json")
        data = {"camera": OBJ_CAMERA, "meshes": [{"file": os.path.relpath(spec.path, folder)}]}
        if spec.materials:
            data["materials"] = spec.materials
        with open(out, "w", encoding="utf-8") as f:
            json.dump(data, f, indent=1)
        return out, ["--allow-outside-paths"]

    def master(self, scene, extra, out_exr, frames, stats=None, sequence=None, bin_dir=None):
        a = self.args
        stats = stats or out_exr.replace(".exr", "-stats.json")
        cmd = [os.path.join(bin_dir or self.bin, "igi-master"), "--scene", scene[0], *scene[1],
               "--local-clients", str(a.clients), "--width", str(a.width), "--height", str(a.height),
               "--frames", str(frames), "--output", out_exr, "--stats-json", stats,
               "--log-level", "error", *extra]
        if sequence:
            cmd += ["--output-sequence", sequence]
        _, wall = run(cmd)
        with open(stats, encoding="utf-8") as f:
            s = json.load(f)
        return {"seconds": s["seconds"], "frames": len(s["frames"]), "wall": wall,
                "shadow_rays_per_pixel": sum(f["shadow_rays_per_pixel"] for f in s["frames"]) / max(1, len(s["frames"]))}

    def compare(self, image, reference):
        proc, _ = run([os.path.join(self.bin, "igi-compare"), image, reference])
        return json.loads(proc.stdout)

    def reference(self, name, scene, factor=1):
        """Our path tracer, two independent halves (seeds 1 and 2) averaged; their difference
        estimates the reference's own noise."""
        a = self.args
        half_frames = a.ref_frames * factor // 2
        total = a.ref_spp * half_frames * 2
        with open(scene[0], "rb") as f:
            digest = hashlib.sha1(f.read()).hexdigest()[:8]
        # The total spp is in the key: references of another sample count are never reused.
        tag = f"{name}-{a.width}x{a.height}-{total}spp-{a.ref_spp}x{half_frames}x2-{digest}"
        ref = os.path.join(a.ref, tag + ".exr")
        meta = os.path.join(a.ref, tag + ".json")
        if os.path.exists(ref) and os.path.exists(meta):
            log(f"{name}: reusing reference {ref}")
            with open(meta, encoding="utf-8") as f:
                return ref, json.load(f)
        halves, seconds = [], 0.0
        for seed in (1, 2):
            half = os.path.join(a.ref, f"{tag}-seed{seed}.exr")
            log(f"{name}: reference half {seed}: path tracer {a.ref_spp} spp x {half_frames} frames")
            r = self.master(scene, ["--integrator", "path", "--spp", str(a.ref_spp), "--seed", str(seed)],
                            half, half_frames)
            seconds += r["seconds"]
            halves.append(half)
        run(["oiiotool", halves[0], halves[1], "--add", "--mulc", "0.5", "-d", "float", "-o", ref])
        between = self.compare(halves[0], halves[1])
        info = {"spp_total": total, "seconds": seconds,
                # relMSE of one half against the other is about twice a half's own relMSE; the
                # mean of both has half a half's variance: floor ~ between / 4.
                "halves_relative_mse": between["relative_mse"],
                "noise_floor_relative_mse": between["relative_mse"] / 4,
                "halves_ssim": between["ssim"]}
        with open(meta, "w", encoding="utf-8") as f:
            json.dump(info, f, indent=1)
        return ref, info

    # ---------------------------------------------------------------- rows
    def add(self, **row):
        image = row.pop("image")
        err = self.compare(image, row.pop("reference"))
        row.update(relmse=err["relative_mse"], ssim=err["ssim"], bias=err["mean_relative_bias"],
                   rmse=err["rmse"], block_error=err["block_relative_error"], speckle=err.get("speckle", float("nan")))
        self.rows.append(row)
        if row["sweep"] in ("frames", "spp"):
            self.images[(row["scene"], row["renderer"], row["frames"] if row["renderer"] != "cycles" else int(row["value"]))] = image
        log(f"  {row['scene']} {row['renderer']} {row['sweep']}={row['value']}: "
            f"{row['time']*1e3:.0f} ms, relMSE {row['relmse']:.4g}, SSIM {row['ssim']:.4f}, "
            f"bias {row['bias']:+.4f}, speckle {row['speckle']:.3g}")

    def igi_sweeps(self, name, scene, ref, specular):
        a = self.args
        d = os.path.join(self.work, name)
        os.makedirs(d, exist_ok=True)
        sweeps = [
            ("indirect_vpls", "--indirect-vpls", a.vpls),
            ("direct_samples", "--direct-samples", a.direct),
        ]
        if specular:
            sweeps.append(("caustic_photons", "--caustic-photons", a.photons))
        for sweep, flag, values in sweeps:
            for v in values:
                out = os.path.join(d, f"igi-{sweep}-{v}.exr")
                r = self.master(scene, [flag, str(v), "--no-accumulate"], out, a.timing_frames)
                self.add(scene=name, renderer="igi", sweep=sweep, value=str(v), frames=1,
                         spf=r["seconds"] / r["frames"], time=r["seconds"] / r["frames"],
                         wall=r["wall"], rays=r["shadow_rays_per_pixel"], image=out, reference=ref)
        for n in a.interleave:
            out = os.path.join(d, f"igi-interleave-{n}.exr")
            r = self.master(scene, ["--interleave", f"{n}x{n}", "--filter", f"{n}x{n}", "--no-accumulate"],
                            out, a.timing_frames)
            self.add(scene=name, renderer="igi", sweep="interleave+filter", value=f"{n}x{n}", frames=1,
                     spf=r["seconds"] / r["frames"], time=r["seconds"] / r["frames"], wall=r["wall"],
                     rays=r["shadow_rays_per_pixel"], image=out, reference=ref)

    def accumulation(self, name, scene, ref, renderer, extra, sweep, bin_dir=None, sequence_frames=True):
        """Accumulation for --seconds of render time: seconds per frame from a short run first,
        then one run of N = max(--min-frames, ceil(seconds x margin / spf)) frames that keeps
        the accumulated images after 1, 2, 4, ..., N frames: the error after k frames, at
        k x (the long run's seconds per frame)."""
        a = self.args
        d = os.path.join(self.work, name)
        os.makedirs(d, exist_ok=True)
        probe = os.path.join(d, f"{renderer}-spf.exr")
        est = self.master(scene, extra + ["--no-accumulate"], probe, a.spf_frames, bin_dir=bin_dir)
        spf_est = est["seconds"] / est["frames"]
        n = max(a.min_frames, math.ceil(a.seconds * a.margin / spf_est))
        if n > a.max_frames:
            self.notes.append(f"{name} {renderer}: {n} frames would be needed for {a.seconds:g} s "
                              f"({spf_est:.3g} s/frame); capped at --max-frames {a.max_frames}")
            n = a.max_frames
        pattern = os.path.join(d, f"{renderer}-acc-%04d.exr")
        out = os.path.join(d, f"{renderer}-acc.exr")

        def session(n):
            ks = frame_counts(n)
            clear_sequence(pattern)
            log(f"{name}: {renderer}: accumulating {n} frames (at {spf_est:.3g} s/frame expected)")
            pruner, more = None, []
            if sequence_frames:
                more = ["--sequence-frames", ",".join(str(k - 1) for k in ks)]
            else:
                pruner = SequencePruner(pattern, [k - 1 for k in ks])
                pruner.start()
            try:
                return ks, self.master(scene, extra + more, out, n, sequence=pattern, bin_dir=bin_dir)
            finally:
                if pruner:
                    pruner.finish()

        ks, r = session(n)
        if r["seconds"] < a.seconds and n < a.max_frames:
            # Faster than the short run said (its pipeline was not full): once more, longer, so
            # that the curve spans --seconds.
            spf_est = r["seconds"] / r["frames"]
            n = min(a.max_frames, max(n + 1, math.ceil(a.seconds * 1.1 / spf_est)))
            ks, r = session(n)
        spf = r["seconds"] / r["frames"]
        self.curves.setdefault(name, {})[renderer] = {"frames": n, "spf": spf, "spf_estimate": spf_est,
                                                     "seconds": r["seconds"], "wall": r["wall"]}
        for k in ks:
            self.add(scene=name, renderer=renderer, sweep=sweep, value=str(k), frames=k, spf=spf,
                     time=spf * k, wall=r["wall"], rays=r["shadow_rays_per_pixel"], image=pattern % (k - 1),
                     reference=ref)

    def compensation(self, name, scene, ref):
        """The choice of what restores the energy the VPL bound removes (`clamp_compensation`): the
        other two choices, accumulated for as many frames as the bias figures use, beside the
        default's curve (Kollig-Keller), at equal frame counts."""
        a = self.args
        d = os.path.join(self.work, name)
        n = max(SLOPE_TO, BIAS_FRAMES) if not a.quick else a.min_frames
        ks = [k for k in (SLOPE_FROM, SPECKLE_FRAMES[-1], n) if k <= n]
        for choice in ("shrink", "off"):
            renderer = f"igi-comp-{choice}"
            pattern = os.path.join(d, f"{renderer}-acc-%04d.exr")
            clear_sequence(pattern)
            log(f"{name}: {renderer}: accumulating {n} frames")
            r = self.master(scene, ["--clamp-compensation", choice, "--sequence-frames",
                                    ",".join(str(k - 1) for k in sorted(set(ks)))],
                            os.path.join(d, f"{renderer}-acc.exr"), n, sequence=pattern)
            spf = r["seconds"] / r["frames"]
            for k in sorted(set(ks)):
                self.add(scene=name, renderer=renderer, sweep="compensation", value=str(k), frames=k, spf=spf,
                         time=spf * k, wall=r["wall"], rays=r["shadow_rays_per_pixel"], image=pattern % (k - 1),
                         reference=ref)

    def first_frame(self, name, scene, ref):
        """One frame of the new and of the baseline build at the same (default) settings: frame 0
        of sessions of --first-frame-frames frames without accumulation, seeds 1..R,
        the builds alternated so that both see the same load. relMSE: mean over the seeds;
        seconds per frame: median of the sessions' throughput."""
        a = self.args
        d = os.path.join(self.work, name)
        os.makedirs(d, exist_ok=True)
        res = {"new": [], "old": []}
        for rep in range(a.first_frame_repeats):
            seed = rep + 1
            order = [("new", self.bin), ("old", self.base_bin)]
            if rep % 2:
                order.reverse()
            for label, b in order:
                pattern = os.path.join(d, f"first-{label}-seed{seed}-%04d.exr")
                clear_sequence(pattern)
                # Without accumulation every frame is a first frame (accumulation 0, the paper's
                # estimator), so the sessions' throughput is the first frame's cost; accumulated
                # frames of the new build would add the converging estimator's extra work.
                extra = ["--seed", str(seed), "--no-accumulate"]
                if label == "new":
                    extra += ["--sequence-frames", "0"]
                r = self.master(scene, extra, os.path.join(d, f"first-{label}-seed{seed}.exr"),
                                a.first_frame_frames, sequence=pattern, bin_dir=b)
                err = self.compare(pattern % 0, ref)
                if label == "old":
                    for k in range(1, r["frames"]):
                        if os.path.exists(pattern % k):
                            os.remove(pattern % k)
                res[label].append({"seed": seed, "relmse": err["relative_mse"], "bias": err["mean_relative_bias"],
                                   "speckle": err.get("speckle"), "spf": r["seconds"] / r["frames"]})
        out = {"runs": res}
        for label in ("new", "old"):
            out[label] = {"relmse": statistics.mean(x["relmse"] for x in res[label]),
                          "spf": statistics.median(x["spf"] for x in res[label]),
                          "bias": statistics.mean(x["bias"] for x in res[label])}
        out["relmse_ratio"] = out["new"]["relmse"] / out["old"]["relmse"]
        out["spf_ratio"] = out["new"]["spf"] / out["old"]["spf"]
        self.first[name] = out
        log(f"{name}: first frame new/old: relMSE {out['new']['relmse']:.4g}/{out['old']['relmse']:.4g} "
            f"= {out['relmse_ratio']:.3f}, s/frame {out['new']['spf']:.4g}/{out['old']['spf']:.4g} = {out['spf_ratio']:.3f}")

    def speckle_seeds(self, name, scene, ref):
        """The speckle claims' figures: one frame's speckle moves by a factor of two from seed
        to seed (a VPL near a crease either is drawn or is not), so the claims are judged on the
        mean over several seeds, SPECKLE_SEEDS[k] sessions of k accumulated frames (seeds 1..),
        not on the accumulation curve's single session."""
        a = self.args
        d = os.path.join(self.work, name)
        os.makedirs(d, exist_ok=True)
        out = {}
        for k in SPECKLE_FRAMES:
            values = []
            for seed in range(1, (2 if a.quick else SPECKLE_SEEDS[k]) + 1):
                image = os.path.join(d, f"speckle-{k}-seed{seed}.exr")
                self.master(scene, ["--seed", str(seed)], image, k)
                values.append(self.compare(image, ref).get("speckle", float("nan")))
            mean = statistics.mean(values)
            stderr = statistics.stdev(values) / math.sqrt(len(values)) if len(values) > 1 else float("nan")
            out[k] = {"mean": mean, "stderr": stderr, "values": values}
            log(f"{name}: speckle after {k} frame(s) over {len(values)} seeds: mean {mean:.3g} "
                f"(standard error {stderr:.2g}; {', '.join(f'{v:.3g}' for v in values)})")
        self.speckle[name] = out

    @staticmethod
    def path_curve():
        """Our path tracer's options for its accumulation curve: 1 spp per frame, PATH_SEED."""
        return ["--integrator", "path", "--spp", "1", "--seed", str(PATH_SEED)]

    def convergence(self, spec, scene, ref):
        name = spec.name
        if spec.speckle:
            self.speckle_seeds(name, scene, ref)
        self.accumulation(name, scene, ref, "igi", [], "frames")
        self.accumulation(name, scene, ref, "igi-off", ["--converge", "off"], "frames")
        self.accumulation(name, scene, ref, "igi-path", self.path_curve(), "spp")
        self.compensation(name, scene, ref)
        if self.base_bin:
            if spec.baseline_skip:
                self.notes.append(f"{name}: no baseline build run: {spec.baseline_skip}.")
                return
            try:
                self.first_frame(name, scene, ref)
                self.accumulation(name, scene, ref, "igi-baseline", [], "frames", bin_dir=self.base_bin,
                                  sequence_frames=False)
            except RuntimeError as e:
                log(f"{name}: the baseline build failed: {e}")
                self.notes.append(f"{name}: the baseline build failed: {str(e).splitlines()[0]}")

    def modes(self, name, scene, ref):
        """The GI modes beside igi and our path tracer, each accumulated for --seconds, and each
        mode's frames alone (what a user sees while things move)."""
        self.accumulation(name, scene, ref, "igi", [], "frames")
        self.alone(name, scene, ref, "igi", [])
        for mode in self.args.modes:
            self.accumulation(name, scene, ref, f"gi-{mode}", ["--gi", mode], "frames")
            self.alone(name, scene, ref, f"gi-{mode}", ["--gi", mode])
        self.accumulation(name, scene, ref, "igi-path", self.path_curve(), "spp")
        for row in self.args.peer_rows.get(name, []):
            self.rows.append(dict(row))

    def alone(self, name, scene, ref, renderer, extra):
        """Frames without accumulation (the frames after a change are what the modes differ
        in): ALONE_FRAMES frames of ALONE_SEEDS sessions, each frame judged alone; the mean
        relMSE and SSIM, and the sessions' seconds per frame."""
        d = os.path.join(self.work, name)
        errs, ssims, spfs = [], [], []
        for seed in range(1, ALONE_SEEDS + 1):
            pattern = os.path.join(d, f"{renderer}-alone-{seed}-%04d.exr")
            clear_sequence(pattern)
            r = self.master(scene, extra + ["--no-accumulate", "--seed", str(seed)],
                            os.path.join(d, f"{renderer}-alone-{seed}.exr"), ALONE_FRAMES, sequence=pattern)
            spfs.append(r["seconds"] / r["frames"])
            for k in range(ALONE_FRAMES):
                e = self.compare(pattern % k, ref)
                errs.append(e["relative_mse"])
                ssims.append(e["ssim"])
        out = {"spf": statistics.median(spfs), "relmse": statistics.mean(errs), "ssim": statistics.mean(ssims),
               "frames": len(errs)}
        self.alone_rows.setdefault(name, {})[renderer] = out
        log(f"  {name} {renderer} alone: {out['spf'] * 1e3:.1f} ms/frame, relMSE {out['relmse']:.4g}, "
            f"SSIM {out['ssim']:.4f} ({out['frames']} frames)")

    # ---------------------------------------------------------------- peers
    def cycles(self, name, scene_path, ref):
        a = self.args
        blender = shutil.which("blender")
        if not blender:
            self.notes.append("Blender was not found: Cycles was not run (install it with --peers).")
            return
        d = os.path.join(self.work, name)
        os.makedirs(d, exist_ok=True)
        prefix = os.path.join(d, "cycles")
        # The shared OBJs get the benchmark camera through their generated scene file.
        cmd = [blender, "-b", "--factory-startup", "-noaudio", "-P", os.path.join(PEERS, "cycles_render.py"), "--",
               scene_path, prefix, str(a.width), str(a.height), str(os.cpu_count() or 2), "1",
               "--until", str(a.seconds), "--max-spp", str(a.cycles_max_spp)]
        log(f"{name}: Blender Cycles, doubling spp until a render takes {a.seconds:g} s")
        try:
            _, wall = run(cmd)
        except RuntimeError as e:
            self.notes.append(f"Blender Cycles failed on {name}: {str(e).splitlines()[0]}")
            return
        with open(prefix + ".json", encoding="utf-8") as f:
            res = json.load(f)
        if res.get("dropped_duplicate_faces"):
            self.notes.append(f"Cycles, {name}: {res['dropped_duplicate_faces']} face(s) repeating another "
                              "face's corners were dropped before rendering (Cycles shadows a face by its twin).")
        for r in res["renders"]:
            self.add(scene=name, renderer="cycles", sweep="spp", value=str(r["spp"]), frames=1,
                     spf=r["seconds"], time=r["seconds"], wall=wall, rays=0.0, image=r["image"], reference=ref)

    def igi_against_cycles(self, name):
        """IGI's accumulated image (BIAS_FRAMES frames, else the most it has) against Cycles'
        render with the most samples: the bias with Cycles as the reference."""
        cyc = {k[2]: v for k, v in self.images.items() if k[0] == name and k[1] == "cycles"}
        igi = {k[2]: v for k, v in self.images.items() if k[0] == name and k[1] == "igi"}
        if not cyc or not igi:
            return
        spp = max(cyc)
        frames = BIAS_FRAMES if BIAS_FRAMES in igi else max(igi)
        err = self.compare(igi[frames], cyc[spp])
        ours = self.compare(cyc[spp], self.ref_images[name])
        self.cycles_bias[name] = {"frames": frames, "cycles_spp": spp, "bias": err["mean_relative_bias"],
                                  "relmse": err["relative_mse"], "cycles_vs_ours_bias": ours["mean_relative_bias"],
                                  "cycles_vs_ours_relmse": ours["relative_mse"]}
        log(f"{name}: igi {frames} frames against Cycles {spp} spp: bias {err['mean_relative_bias']:+.4f} "
            f"(Cycles against our reference: {ours['mean_relative_bias']:+.4f})")

    def embree_probe(self, name, scene_path):
        """Embree's pathtracer tutorial (3.13) drops quad and triangle lights when it converts its
        scene graph ('not implemented'), so area-lit scenes render black. This probe renders the
        scene with its area lights and records the image's mean, so the document states a
        measured fact rather than a reading of the source."""
        exe = shutil.which("pathtracer")
        if not exe:
            return None
        d = os.path.join(self.work, name)
        flat = igi_scene.flatten(scene_path, self.args.width, self.args.height)
        xml = os.path.join(d, "embree.xml")
        embree_scene.write(flat, xml, 1.0)
        pfm = os.path.join(d, "embree-probe.pfm")
        _, wall = run([exe, "-i", xml, *embree_scene.camera_args(flat), "--size", str(self.args.width),
                       str(self.args.height), "--spp", "4", "--max-path-length", "16",
                       "--threads", str(os.cpu_count() or 2), "-o", pfm])
        proc, _ = run(["oiiotool", pfm, "--printstats"])
        m = re.search(r"Stats Avg:\s*([-\d.e]+)\s+([-\d.e]+)\s+([-\d.e]+)", proc.stdout)
        mean = sum(float(x) for x in m.groups()) / 3 if m else float("nan")
        return {"scene": name, "mean": mean, "wall": wall}

    # ---------------------------------------------------------------- all
    def run_all(self):
        a = self.args
        self.ref_images = {}
        self.requested = []
        for spec in SCENES:
            if a.scenes and spec.name not in a.scenes:
                continue
            if not os.path.exists(spec.path):
                log(f"{spec.name}: {spec.path} is missing, skipped")
                self.notes.append(f"{spec.name} skipped: {spec.path} missing")
                continue
            self.requested.append(spec.name)
            try:
                self.run_scene(spec)
            except RuntimeError as e:
                # A long run goes on with the other scenes; the failure is in the notes, and this
                # scene's claims are reported as not evaluated.
                log(f"{spec.name}: FAILED: {e}")
                self.notes.append(f"{spec.name}: the run failed: {str(e).splitlines()[0]}")

    def run_scene(self, spec):
        a = self.args
        scene = self.scene_file(spec)
        ref, info = self.reference(spec.name, scene, 1 if a.quick else spec.ref_factor)
        self.refs[spec.name] = info
        self.ref_images[spec.name] = ref
        log(f"{spec.name}: reference {info['spp_total']} spp, noise floor relMSE ~ {info['noise_floor_relative_mse']:.2g}")
        if a.references_only:
            return
        if a.modes:
            self.modes(spec.name, scene, ref)
            return
        if spec.sweeps and a.sweeps:
            self.igi_sweeps(spec.name, scene, ref, spec.specular)
        self.convergence(spec, scene, ref)
        if a.peers and spec.cycles:
            self.cycles(spec.name, scene[0], ref)
            self.igi_against_cycles(spec.name)
        if a.peers and spec.probe:
            probe = self.embree_probe(spec.name, scene[0])
            if probe:
                self.probes.append(probe)


# -------------------------------------------------------------------- analysis
def curve(rows, scene, renderer):
    """(time, relMSE, row) of a renderer's accumulation (or Cycles') curve, by time. A render
    that took as long as or longer than one with more samples is left out (whoever wants that
    accuracy renders the larger count), so that time grows along the curve."""
    sweep = "spp" if renderer in ("igi-path", "cycles") else "frames"
    pts = sorted((r for r in rows if r["scene"] == scene and r["renderer"] == renderer and r["sweep"] == sweep),
                 key=lambda r: int(r["value"]))
    kept = [r for i, r in enumerate(pts) if all(r["time"] < q["time"] for q in pts[i + 1:])]
    return [(r["time"], r["relmse"], r) for r in kept]


def at_frames(rows, scene, renderer, k):
    for r in rows:
        if r["scene"] == scene and r["renderer"] == renderer and r["sweep"] in ("frames", "spp", "compensation") and r["frames"] == k:
            return r
    return None


def loglog(points, t):
    """The error at time t on the curve, linear in log-log between its points; "before" if the
    curve has no image yet at t, None past its end."""
    if t < points[0][0] * (1 - 1e-9):
        return "before"
    if t > points[-1][0] * (1 + 1e-9):
        return None
    for (t0, e0, _), (t1, e1, _) in zip(points, points[1:]):
        if t0 <= t <= t1:
            if t1 <= t0:
                return e1
            w = math.log(t / t0) / math.log(t1 / t0)
            return math.exp(math.log(e0) + w * (math.log(e1) - math.log(e0)))
    return points[-1][1]


def below(igi, other, t_end, floor=0.0):
    """Whether IGI's curve is below the other's at every time from IGI's first frame to t_end
    (a dense log grid plus every point of both curves); where the other has no image yet, IGI
    is below. worst_ratio: the largest IGI / other relMSE met (floor: subtracted from both)."""
    if not igi or not other:
        return None
    t0 = igi[0][0]
    t_stop = min(t_end, igi[-1][0], other[-1][0])
    if t_stop < t0:
        return None
    grid = [t0 * (t_stop / t0) ** (i / 400) for i in range(401)] if t_stop > t0 else [t0]
    grid += [p[0] for p in igi + other if t0 <= p[0] <= t_stop]
    worst, worst_t = 0.0, t0
    for t in sorted(grid):
        e_i, e_o = loglog(igi, t), loglog(other, t)
        if e_o == "before" or e_i is None or e_o is None or e_i == "before":
            continue
        e_i, e_o = e_i - floor, e_o - floor
        if e_o <= 0:
            if e_i <= 0:
                continue  # both within the reference's noise: no difference to see
            ratio = math.inf
        else:
            ratio = max(e_i, 0.0) / e_o
        if ratio > worst:
            worst, worst_t = ratio, t
    return {"holds": worst < 1.0, "worst_ratio": worst, "at_seconds": worst_t, "until_seconds": t_stop,
            "covers": t_stop >= t_end * 0.999, "other_starts": other[0][0]}


def slope(e_from, e_to, k_from, k_to, floor=0.0):
    a, b = e_from - floor, e_to - floor
    if a <= 0 or b <= 0:
        return None
    return math.log(b / a) / math.log(k_to / k_from)


def analyse(bench):
    """Per scene: the convergence figures the claims are judged on."""
    rows, a = bench.rows, bench.args
    conv = {}
    for scene, info in bench.refs.items():
        floor = info["noise_floor_relative_mse"]
        c = {"floor": floor, "curves": bench.curves.get(scene, {})}
        for k in (1, 16, BIAS_FRAMES):
            r = at_frames(rows, scene, "igi", k)
            c[f"bias_{k}"] = r["bias"] if r else None
            r = at_frames(rows, scene, "igi-off", k)
            c[f"bias_off_{k}"] = r["bias"] if r else None
        for k in SPECKLE_FRAMES:
            r = at_frames(rows, scene, "igi", k)
            c[f"speckle_{k}"] = r["speckle"] if r else None
        for renderer, key in (("igi", ""), ("igi-off", "_off"), ("igi-baseline", "_baseline"), ("igi-path", "_path")):
            r0, r1 = at_frames(rows, scene, renderer, SLOPE_FROM), at_frames(rows, scene, renderer, SLOPE_TO)
            c["relmse_16" + key] = r0["relmse"] if r0 else None
            c["relmse_256" + key] = r1["relmse"] if r1 else None
            c["slope_raw" + key] = slope(r0["relmse"], r1["relmse"], SLOPE_FROM, SLOPE_TO) if r0 and r1 else None
            c["slope_floor" + key] = slope(r0["relmse"], r1["relmse"], SLOPE_FROM, SLOPE_TO, floor) if r0 and r1 else None
            c["at_floor" + key] = bool(r1 and r1["relmse"] <= floor)
        igi = curve(rows, scene, "igi")
        for other in ("igi-path", "cycles"):
            oc = curve(rows, scene, other)
            c["below_" + other] = below(igi, oc, a.seconds)
            c["below_" + other + "_floor"] = below(igi, oc, a.seconds, floor)
        c["cycles_bias"] = bench.cycles_bias.get(scene)
        conv[scene] = c
    return conv


def verdict(ok):
    return {True: "HOLDS", False: "DOES NOT HOLD", None: "NOT EVALUATED"}[ok]


def pct(x, digits=2):
    return "n/a" if x is None else f"{100 * x:+.{digits}f} %"


def judge(bench, conv):
    """The claims of the convergence part, each with its verdict and the numbers behind it."""
    a = bench.args
    claims = []

    def claim(cid, text, ok, detail):
        claims.append({"id": cid, "claim": text, "holds": ok, "detail": detail})

    # 1. Speckle, each figure the mean over several seeds (Bench.speckle_seeds).
    g, d = bench.speckle.get("interior-glossy"), bench.speckle.get("interior-diffuse")

    def seeds(s):
        return f"{s['mean']:.3g} +- {s['stderr']:.2g} ({len(s['values'])} seeds)"

    for k in SPECKLE_FRAMES:
        text = f"speckle after {k} frame(s), mean over seeds: interior-glossy <= interior-diffuse"
        if g and d and k in g and k in d:
            claim(f"1-speckle-{k}", text, g[k]["mean"] <= d[k]["mean"],
                  f"glossy {seeds(g[k])}, diffuse {seeds(d[k])}")
        else:
            claim(f"1-speckle-{k}", text, None, "both interiors are needed")
    cg = bench.speckle.get("cornell-glossy")
    k = SPECKLE_FRAMES[-1]
    text = f"speckle after {k} frames on cornell-glossy is 0 (every seed)"
    if cg and k in cg:
        claim("1-speckle-cornell-glossy", text, max(cg[k]["values"]) == 0,
              ", ".join(f"{v:.3g}" for v in cg[k]["values"]))
    else:
        claim("1-speckle-cornell-glossy", text, None, "not run")

    missing = [s for s in bench.requested if s not in conv]
    for scene in missing:
        claim(f"2-3-{scene}", f"{scene}: bias, slope and equal-time claims", None, "the scene's run failed (notes)")

    # 2. Bias.
    for scene, c in conv.items():
        b = c[f"bias_{BIAS_FRAMES}"]
        claim(f"2-bias-{scene}", f"{scene}: |bias| <= {BIAS_LIMIT:.1%} after {BIAS_FRAMES} frames",
              None if b is None else abs(b) <= BIAS_LIMIT,
              f"{pct(b)} (1 frame {pct(c['bias_1'])}, 16 frames {pct(c['bias_16'])}; converge off: "
              f"{pct(c[f'bias_off_{BIAS_FRAMES}'])})" if b is not None else
              f"fewer than {BIAS_FRAMES} frames were rendered")
    for spec in SCENES:
        if spec.name not in conv or not spec.cycles_match:
            continue
        cb = conv[spec.name]["cycles_bias"]
        claim(f"2-bias-cycles-{spec.name}", f"{spec.name}: |bias| <= {BIAS_LIMIT:.1%} against Cycles' reference",
              None if cb is None or cb["frames"] != BIAS_FRAMES else abs(cb["bias"]) <= BIAS_LIMIT,
              "Cycles not run (--peers)" if cb is None else
              f"{pct(cb['bias'])} (igi {cb['frames']} frames against Cycles {cb['cycles_spp']} spp; "
              f"Cycles against our reference {pct(cb['cycles_vs_ours_bias'])})")

    # 3. The trade keeps paying.
    for scene, c in conv.items():
        raw, corr = c["slope_raw"], c["slope_floor"]
        if raw is None:
            ok, detail = None, f"fewer than {SLOPE_TO} frames were rendered"
        elif corr is None and c["at_floor"]:
            ok, detail = True, f"raw {raw:.2f}; the {SLOPE_TO}-frame error is within the reference's noise floor"
        else:
            ok = corr is not None and corr <= SLOPE_LIMIT
            detail = f"floor-corrected {num(corr)} (raw {raw:.2f}); converge off: raw {num(c['slope_raw_off'])}"
        claim(f"3-slope-{scene}", f"{scene}: relMSE slope {SLOPE_FROM}->{SLOPE_TO} frames <= {SLOPE_LIMIT} "
              "(floor-corrected)", ok, detail)
        for other, label in (("igi-path", "our path tracer"), ("cycles", "Cycles")):
            b = c["below_" + other]
            if b is None:
                if other == "cycles":
                    continue  # Cycles not run on this scene (its materials, or no --peers)
                claim(f"3-below-{other}-{scene}", f"{scene}: igi below {label} up to {a.seconds:g} s", None, "no curve")
                continue
            ok = b["holds"] and b["covers"]
            detail = (f"worst igi/{other} relMSE ratio {num(b['worst_ratio'])} at {b['at_seconds']:.3g} s"
                      + ("" if b["covers"] else f"; the curves end at {b['until_seconds']:.3g} s"))
            if not b["holds"] or not b["covers"]:
                ok = False if not b["holds"] else None
            claim(f"3-below-{other}-{scene}", f"{scene}: igi below {label} from one frame up to {a.seconds:g} s",
                  ok, detail)

    # 4. The first frame against the baseline build.
    if not bench.base_bin:
        claim("4-first-frame", "first frame within 10 % of the previous build", None, "no --baseline-build given")
    else:
        for scene in FIRST_FRAME_SCENES:
            f = bench.first.get(scene)
            if f is None:
                if scene in conv:
                    claim(f"4-first-frame-{scene}", f"{scene}: first frame within 10 % of the previous build", None,
                          "not run")
                continue
            ok = f["relmse_ratio"] <= FIRST_FRAME_LIMIT and f["spf_ratio"] <= FIRST_FRAME_LIMIT
            claim(f"4-first-frame-{scene}", f"{scene}: first frame relMSE and s/frame new/old <= {FIRST_FRAME_LIMIT}",
                  ok, f"relMSE ratio {f['relmse_ratio']:.3f} ({f['new']['relmse']:.4g} / {f['old']['relmse']:.4g}), "
                      f"s/frame ratio {f['spf_ratio']:.3f} ({f['new']['spf']:.4g} / {f['old']['spf']:.4g})")
    return claims


# -------------------------------------------------------------------- reporting
def pareto(points):
    """Indices of the points no other point beats in both time and error."""
    order = sorted(range(len(points)), key=lambda i: (points[i][0], points[i][1]))
    front, best = [], float("inf")
    for i in order:
        if points[i][1] < best:
            front.append(i)
            best = points[i][1]
    return front


def mark_pareto(rows):
    for scene in sorted({r["scene"] for r in rows}):
        sub = [r for r in rows if r["scene"] == scene]
        for i in pareto([(r["time"], r["relmse"]) for r in sub]):
            sub[i]["pareto"] = True
    for r in rows:
        r.setdefault("pareto", False)


STYLE = {
    ("igi", "indirect_vpls"): ("o", "tab:blue", ":", "igi: indirect VPLs per set"),
    ("igi", "direct_samples"): ("s", "tab:orange", ":", "igi: light samples"),
    ("igi", "caustic_photons"): ("^", "tab:purple", ":", "igi: caustic photons per set"),
    ("igi", "interleave+filter"): ("D", "tab:brown", ":", "igi: interleave = filter (1x1..4x4)"),
    ("igi", "frames"): ("o", "tab:red", "-", "igi (default, converging), accumulated frames"),
    ("igi-off", "frames"): ("o", "salmon", "--", "igi --converge off (the paper's estimator)"),
    ("igi-baseline", "frames"): ("o", "tab:pink", "-.", "igi, baseline (previous) build"),
    ("igi-path", "spp"): ("x", "tab:gray", "-", "our path tracer, 1 spp per frame, accumulated"),
    ("cycles", "spp"): ("v", "tab:green", "-", "Blender Cycles (CPU), samples per pixel"),
    ("gi-cache", "frames"): ("P", "tab:cyan", "-", "--gi cache (instant caching), accumulated frames"),
    ("gi-photonmap", "frames"): ("*", "tab:olive", "-", "--gi photonmap (Larsen-Christensen), accumulated frames"),
    ("gi-spt", "frames"): ("h", "tab:purple", "-", "--gi spt, accumulated frames"),
    ("gi-stream", "frames"): ("<", "tab:brown", "-", "--gi stream, accumulated frames"),
}


def plot(rows, scene, path, refinfo, seconds):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    sub = [r for r in rows if r["scene"] == scene]
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.6))
    for ax, key, label in ((axes[0], "relmse", "relative MSE"), (axes[1], "dssim", "1 - SSIM")):
        for (renderer, sweep), (marker, colour, line, name) in STYLE.items():
            pts = [r for r in sub if r["renderer"] == renderer and r["sweep"] == sweep]
            # Curves in order of frames or samples (a Cycles render can take less time than the
            # one before it: start-up), sweeps in order of time.
            pts.sort(key=(lambda r: int(r["value"])) if sweep in ("frames", "spp") else (lambda r: r["time"]))
            if not pts:
                continue
            ys = [r["relmse"] if key == "relmse" else max(1e-5, 1 - r["ssim"]) for r in pts]
            ax.plot([r["time"] for r in pts], ys, line, marker=marker, color=colour, label=name, alpha=0.85,
                    markersize=4)
            if sweep not in ("frames", "spp"):
                for r, y in zip(pts, ys):
                    ax.annotate(r["value"], (r["time"], y), fontsize=6, xytext=(3, 3), textcoords="offset points")
        if key == "relmse":
            front = sorted([r for r in sub if r["pareto"]], key=lambda r: r["time"])
            xs, ys = [], []
            for r in front:
                if xs:
                    xs.append(r["time"])
                    ys.append(ys[-1])
                xs.append(r["time"])
                ys.append(r["relmse"])
            ax.plot(xs, ys, "k--", lw=0.8, alpha=0.6, label="Pareto front (all points)")
            floor = refinfo.get("noise_floor_relative_mse")
            if floor:
                ax.axhline(floor, color="k", lw=0.8, alpha=0.6, label="reference noise floor (halves / 4)")
        ax.axvline(seconds, color="k", lw=0.5, ls=":", alpha=0.5)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("render time of the image, seconds (log)")
        ax.set_ylabel(label + " (log)")
        ax.grid(True, which="both", alpha=0.3)
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=8)
    fig.suptitle(f"{scene}: error against time (reference: our path tracer, {refinfo.get('spp_total', '?')} spp)")
    fig.tight_layout(rect=(0, 0.14, 1, 1))
    fig.savefig(path, dpi=110)
    plt.close(fig)


def fmt(x, digits=3):
    return f"{x:.{digits}g}"


def table(rows, scene):
    sub = [r for r in rows if r["scene"] == scene]
    lines = ["| renderer | parameter | value | frames | s/frame | time (s) | wall (s) | shadow rays/px | relMSE | SSIM | bias | speckle | Pareto |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in sub:
        lines.append(f"| {r['renderer']} | {r['sweep']} | {r['value']} | {r['frames']} | {fmt(r['spf'])} | "
                     f"{fmt(r['time'])} | {r['wall']:.1f} | {r['rays']:.1f} | {fmt(r['relmse'])} | {r['ssim']:.4f} | "
                     f"{r['bias']:+.4f} | {fmt(r['speckle'])} | {'**yes**' if r['pareto'] else ''} |")
    return "\n".join(lines)


def convergence_tables(bench, conv):
    a = bench.args
    t1 = ["| scene | frames (igi / off / path) | s/frame igi | bias 1 | bias 16 | bias 256 | bias 256, converge off | "
          "bias 256 against Cycles | slope 16→256 raw | slope floor-corrected | slope, converge off (raw) | "
          "speckle 1 | speckle 32 |",
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    t2 = [f"| scene | igi below our path tracer up to {a.seconds:g} s | worst igi / path relMSE | "
          f"igi below Cycles up to {a.seconds:g} s | worst igi / Cycles relMSE | worst ratios, floor subtracted "
          "(path, Cycles) |",
          "|---|---|---|---|---|---|"]

    def yes(b):
        if b is None:
            return "n/a"
        text = "yes" if b["holds"] else "**no**"
        return text if b["covers"] else f"{text} (curves end at {b['until_seconds']:.3g} s)"

    def ratio(b):
        return "n/a" if b is None else f"{num(b['worst_ratio'])} at {b['at_seconds']:.3g} s"

    for scene, c in conv.items():
        cur = c["curves"]
        frames = " / ".join(str(cur[r]["frames"]) if r in cur else "-" for r in ("igi", "igi-off", "igi-path"))
        spf = num(cur["igi"]["spf"]) if "igi" in cur else "n/a"
        cb = c["cycles_bias"]
        cyc = "n/a" if cb is None else f"{pct(cb['bias'])} ({cb['cycles_spp']} spp)"
        corr = num(c["slope_floor"])
        if c["slope_floor"] is None and c["at_floor"]:
            corr = "at floor"
        t1.append(f"| {scene} | {frames} | {spf} | {pct(c['bias_1'])} | {pct(c['bias_16'])} | "
                  f"{pct(c[f'bias_{BIAS_FRAMES}'])} | {pct(c[f'bias_off_{BIAS_FRAMES}'])} | {cyc} | "
                  f"{num(c['slope_raw'])} | {corr} | {num(c['slope_raw_off'])} | {num(c['speckle_1'])} | "
                  f"{num(c['speckle_32'])} |")
        bp, bc = c["below_igi-path"], c["below_cycles"]
        bpf, bcf = c["below_igi-path_floor"], c["below_cycles_floor"]
        t2.append(f"| {scene} | {yes(bp)} | {ratio(bp)} | {yes(bc)} | {ratio(bc)} | "
                  f"{num(bpf['worst_ratio']) if bpf else 'n/a'}, {num(bcf['worst_ratio']) if bcf else 'n/a'} |")
    return "\n".join(t1) + "\n\n" + "\n".join(t2)


def compensation_table(bench, conv):
    """relMSE and bias of the three `clamp_compensation` choices at equal accumulated frames."""
    rows = bench.rows
    ks = sorted({r["frames"] for r in rows if r["renderer"].startswith("igi-comp-")})
    if not ks:
        return "- not run"
    head = " | ".join(f"relMSE after {k}" for k in ks)
    lines = ["relMSE (and bias) at equal accumulated frames; `kollig-keller` is the default curve above, "
             "the other two are sessions of their own with only `--clamp-compensation` changed; "
             "s/frame from each session",
             "",
             f"| scene | choice | s/frame | {head} | bias after {ks[-1]} |",
             "|---|---|---|" + "---|" * len(ks) + "---|"]
    for scene in conv:
        best = {}
        cells = {}
        for choice, renderer in (("kollig-keller", "igi"), ("shrink", "igi-comp-shrink"), ("off", "igi-comp-off")):
            at = [at_frames(rows, scene, renderer, k) for k in ks]
            cells[choice] = at
            for k, r in zip(ks, at):
                if r and (k not in best or r["relmse"] < best[k]):
                    best[k] = r["relmse"]
        for choice, at in cells.items():
            spf = next((num(r["spf"]) for r in at if r), "n/a")
            errs = " | ".join("n/a" if r is None else (f"**{num(r['relmse'])}**" if r["relmse"] == best.get(k) else num(r["relmse"]))
                              for k, r in zip(ks, at))
            bias = pct(at[-1]["bias"]) if at[-1] else "n/a"
            lines.append(f"| {scene} | {choice} | {spf} | {errs} | {bias} |")
    lines.append("")
    lines.append("Bold: the lowest relMSE of the three at that frame count.")
    return "\n".join(lines)


def first_frame_table(bench, conv):
    if not bench.base_bin:
        return "- no baseline build given (`scripts/bench_accuracy.sh --baseline-build DIR`)"
    a = bench.args
    lines = [f"- baseline build: `{bench.base_bin}`; {a.first_frame_repeats} sessions of {a.first_frame_frames} frames "
             "without accumulation per build and scene (seeds 1, 2, ...), the builds alternated; relMSE of the first frame: mean over the "
             "seeds; seconds per frame: median of the sessions' throughput",
             "",
             "| scene | relMSE new | relMSE old | ratio | s/frame new | s/frame old | ratio | bias new | bias old | "
             f"relMSE {BIAS_FRAMES} frames new / old | within {FIRST_FRAME_LIMIT:.2f} |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for scene in conv:
        f = bench.first.get(scene)
        if f is None:
            spec = next(s for s in SCENES if s.name == scene)
            lines.append(f"| {scene} | {spec.baseline_skip or 'not run'} | | | | | | | | | |")
            continue
        new, old = at_frames(bench.rows, scene, "igi", BIAS_FRAMES), at_frames(bench.rows, scene, "igi-baseline", BIAS_FRAMES)
        acc = f"{num(new['relmse'])} / {num(old['relmse'])}" if new and old else "n/a"
        ok = f["relmse_ratio"] <= FIRST_FRAME_LIMIT and f["spf_ratio"] <= FIRST_FRAME_LIMIT
        lines.append(f"| {scene} | {num(f['new']['relmse'])} | {num(f['old']['relmse'])} | {f['relmse_ratio']:.3f} | "
                     f"{num(f['new']['spf'])} | {num(f['old']['spf'])} | {f['spf_ratio']:.3f} | {pct(f['new']['bias'])} | "
                     f"{pct(f['old']['bias'])} | {acc} | {'yes' if ok else '**no**'} |")
    return "\n".join(lines)


def claims_block(claims, smoke):
    lines = []
    if smoke:
        lines.append("- **smoke run** (--quick, or a reference under 4096 spp, or curves under 60 s or 256 frames): "
                     "these verdicts are not evidence for the claims")
    for c in claims:
        lines.append(f"- **{verdict(c['holds'])}**: {c['claim']}: {c['detail']}")
    return "\n".join(lines)


def write_reports(bench, docs, command, started):
    rows = bench.rows
    mark_pareto(rows)
    os.makedirs(docs, exist_ok=True)
    fields = ["scene", "renderer", "sweep", "value", "frames", "spf", "time", "wall", "rays", "relmse", "ssim",
              "bias", "speckle", "rmse", "block_error", "pareto"]
    with open(os.path.join(docs, "results.csv"), "w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        for r in rows:
            w.writerow({k: r[k] for k in fields})
    end = machine()
    a = bench.args
    conv = analyse(bench)
    claims = judge(bench, conv)
    parts = {}
    sweeps = (f"sweep points rendered {a.timing_frames} frames each without accumulation (time per frame = "
              "throughput)" if a.sweeps else "no parameter sweeps (--no-sweeps)")
    parts["machine"] = "\n".join([
        f"- command: `{command}`",
        f"- machine: {end['nproc']} cores ({end['cpu']}), kernel {end['kernel']}",
        f"- started {started['date']} (load average {started['load']}), finished {end['date']} (load {end['load']})",
        f"- resolution {a.width} x {a.height}, {a.clients} local clients; {sweeps}; accumulation curves for "
        f"{a.seconds:g} s of render time (at least {a.min_frames} frames)",
        "- the machine's two cores are shared with other work: timings carry that noise",
    ])
    refs = ["| scene | reference spp | reference time (s) | noise floor relMSE (halves / 4) | SSIM between halves |",
            "|---|---|---|---|---|"]
    for scene, info in bench.refs.items():
        refs.append(f"| {scene} | {info['spp_total']} | {info['seconds']:.0f} | {fmt(info['noise_floor_relative_mse'])} | "
                    f"{info['halves_ssim']:.4f} |")
    parts["references"] = "\n".join(refs)
    parts["convergence"] = convergence_tables(bench, conv)
    parts["first-frame"] = first_frame_table(bench, conv)
    parts["compensation"] = compensation_table(bench, conv)
    parts["claims"] = claims_block(claims, not a.evidence)
    scene_parts = []
    for scene in bench.refs:
        png = f"{scene}.png"
        plot(rows, scene, os.path.join(docs, png), bench.refs[scene], a.seconds)
        scene_parts.append(f"### {scene}\n\n![{scene}: error against time](accuracy/{png})\n\n{table(rows, scene)}\n")
    parts["results"] = "\n".join(scene_parts)
    notes = list(bench.notes)
    for p in bench.probes:
        notes.append(f"Embree pathtracer probe on {p['scene']} (scene with its area lights, 4 spp): "
                     f"image mean {p['mean']:.4g} (0 = black: its area lights are not rendered).")
    parts["notes"] = "\n".join(f"- {n}" for n in notes) if notes else "- none"
    with open(os.path.join(docs, "results.md"), "w", encoding="utf-8") as f:
        for key in ("machine", "claims", "references", "convergence", "first-frame", "compensation", "results",
                    "notes"):
            f.write(f"## {key}\n\n{parts[key]}\n\n")
    with open(os.path.join(docs, "summary.json"), "w", encoding="utf-8") as f:
        json.dump({"machine_start": started, "machine_end": end, "command": command, "quick": a.quick,
                   "evidence": a.evidence,
                   "settings": {"width": a.width, "height": a.height, "clients": a.clients, "seconds": a.seconds,
                                "min_frames": a.min_frames, "baseline_build": a.baseline_build},
                   "references": bench.refs, "notes": notes, "claims": claims, "convergence": conv,
                   "first_frame": bench.first, "cycles_bias": bench.cycles_bias, "speckle_seeds": bench.speckle,
                   "pareto": [r for r in rows if r["pareto"]]}, f, indent=1, default=str)
    return parts, claims


MODE_TIMES = (0.1, 1.0, 10.0)
ALONE_FRAMES, ALONE_SEEDS = 8, 2  # frames without accumulation per session, sessions  # seconds of render time at which the modes' table reads the curves


def load_peer_rows(path, width, height, scenes):
    """Cycles' rows of a main run's results.csv, if that run was at this size: the Pareto front
    of a modes run is drawn with them (Cycles is not re-run; its times come from that run)."""
    if not path or not os.path.exists(path):
        return {}, "no peer rows"
    summary = os.path.join(os.path.dirname(path), "summary.json")
    try:
        with open(summary, encoding="utf-8") as f:
            settings = json.load(f)["settings"]
    except (OSError, KeyError, ValueError):
        return {}, f"{summary} unreadable: no peer rows"
    if (settings.get("width"), settings.get("height")) != (width, height):
        return {}, f"{path} is at {settings.get('width')} x {settings.get('height')}: Cycles not shown"
    out = {}
    with open(path, encoding="utf-8") as f:
        for r in csv.DictReader(f):
            if r["renderer"] != "cycles" or (scenes and r["scene"] not in scenes):
                continue
            row = {k: r[k] for k in ("scene", "renderer", "sweep", "value")}
            row["frames"] = int(r["frames"])
            for k in ("spf", "time", "wall", "rays", "relmse", "ssim", "bias", "speckle", "rmse", "block_error"):
                row[k] = float(r[k]) if r.get(k) not in (None, "") else float("nan")
            out.setdefault(r["scene"], []).append(row)
    return out, f"Cycles' points from {os.path.relpath(path, ROOT)} (its own run, same machine and size)"


def modes_table(bench, scene, renderers):
    rows = bench.rows
    head = ("| renderer | frames alone (--no-accumulate): s/frame, relMSE, SSIM | "
            "s/frame accumulating | first frame: relMSE / SSIM / bias | "
            + " | ".join(f"relMSE at {t:g} s" for t in MODE_TIMES)
            + " | relMSE at the end (time) | bias at the end | on the Pareto front |")
    lines = [head, "|" + "---|" * (7 + len(MODE_TIMES))]
    alone = bench.alone_rows.get(scene, {})
    base = alone.get("igi")
    igi = curve(rows, scene, "igi")
    for renderer in renderers:
        pts = curve(rows, scene, renderer)
        if not pts:
            continue
        first = pts[0][2]
        cells = []
        for t in MODE_TIMES:
            e = loglog(pts, t)
            if e in ("before", None):
                cells.append("-")
                continue
            ref = loglog(igi, t) if igi and renderer != "igi" else None
            ratio = f" ({e / ref:.2f} x igi)" if isinstance(ref, float) else ""
            cells.append(f"{fmt(e)}{ratio}")
        last = pts[-1][2]
        front = [r for r in rows if r["scene"] == scene and r["renderer"] == renderer and r.get("pareto")]
        span = (f"{len(front)} points, {fmt(min(r['time'] for r in front))}-{fmt(max(r['time'] for r in front))} s"
                if front else "no")
        spf = "n/a" if renderer == "cycles" else fmt(last["spf"])  # Cycles' points are separate renders
        al = alone.get(renderer)
        if al:
            vs = (f" ({al['relmse'] / base['relmse']:.2f} x igi's, at {al['spf'] / base['spf']:.2f} x its time)"
                  if base and renderer != "igi" else "")
            al_cell = f"{fmt(al['spf'])} s, {fmt(al['relmse'])}, {al['ssim']:.4f}{vs}"
        else:
            al_cell = "n/a"
        lines.append(f"| {renderer} | {al_cell} | {spf} | {fmt(first['relmse'])} / {first['ssim']:.4f} / "
                     f"{first['bias']:+.4f} | " + " | ".join(cells)
                     + f" | {fmt(last['relmse'])} ({fmt(last['time'])} s) | {last['bias']:+.4f} | {span} |")
    return "\n".join(lines)


def write_modes_report(bench, docs, command, started):
    a = bench.args
    rows = bench.rows
    mark_pareto(rows)
    os.makedirs(docs, exist_ok=True)
    fields = ["scene", "renderer", "sweep", "value", "frames", "spf", "time", "wall", "rays", "relmse", "ssim",
              "bias", "speckle", "pareto"]
    with open(os.path.join(docs, "results.csv"), "w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow(r)
    end = machine()
    renderers = ["igi"] + [f"gi-{m}" for m in a.modes] + ["igi-path", "cycles"]
    sub = os.path.basename(os.path.normpath(docs))
    out = [f"- command: `{command}`",
           f"- machine: {end['nproc']} cores ({end['cpu']}), kernel {end['kernel']}; started {started['date']} "
           f"(load {started['load']}), finished {end['date']} (load {end['load']}); shared cores, timings carry "
           "that noise",
           f"- {a.width} x {a.height}, {a.clients} local clients; every renderer accumulated for {a.seconds:g} s "
           f"of render time (at least {a.min_frames} frames); {a.peer_note}",
           f"- frames alone: {ALONE_SEEDS} sessions of {ALONE_FRAMES} frames with --no-accumulate (seeds 1, 2), "
           "each frame judged alone, relMSE and SSIM their mean, s/frame the sessions' median throughput; "
           "the accumulating columns: one session accumulated for the time given, its images after 1, 2, 4, ... "
           "frames (an accumulated frame of igi's converging estimator costs more than a frame alone, "
           "and the cache computes records for each accumulated frame's own light paths)",
           "- relMSE at t: the curve read at t seconds of render time (log-log between its images), and "
           "its ratio to igi's at the same time; '-' where the renderer has no image yet at t or its curve "
           "ended before", ""]
    for scene in bench.refs:
        info = bench.refs[scene]
        png = f"{scene}.png"
        plot(rows, scene, os.path.join(docs, png), info, a.seconds)
        out += [f"#### {scene} ({a.width} x {a.height}; reference {info['spp_total']} spp, noise floor relMSE "
                f"{fmt(info['noise_floor_relative_mse'])})", "",
                modes_table(bench, scene, renderers), "", f"![{scene}: the modes' error against time](accuracy/{sub}/{png})", ""]
    if bench.notes:
        out += [f"- {n}" for n in bench.notes]
    text = "\n".join(out).rstrip() + "\n"
    with open(os.path.join(docs, "results.md"), "w", encoding="utf-8") as f:
        f.write(text)
    with open(os.path.join(docs, "summary.json"), "w", encoding="utf-8") as f:
        json.dump({"machine_start": started, "machine_end": end, "command": command,
                   "settings": {"width": a.width, "height": a.height, "clients": a.clients, "seconds": a.seconds,
                                "min_frames": a.min_frames, "modes": a.modes},
                   "references": bench.refs, "curves": bench.curves, "notes": bench.notes,
                   "alone": bench.alone_rows,
                   "pareto": [r for r in rows if r["pareto"]]}, f, indent=1, default=str)
    return {f"modes-{a.width}x{a.height}": text.rstrip()}


def print_summary(claims, smoke, docs):
    print("", flush=True)
    print("=" * 100)
    print("Claims" + (" (SMOKE RUN: weak reference or short curves; not evidence)" if smoke else ""))
    print("=" * 100)
    for c in claims:
        print(f"{verdict(c['holds']):>14}  {c['claim']}\n{'':>16}{c['detail']}")
    counts = {v: sum(1 for c in claims if c["holds"] is k) for k, v in ((True, "hold"), (False, "fail"), (None, "n/a"))}
    print("-" * 100)
    print(f"{counts['hold']} hold, {counts['fail']} do not hold, {counts['n/a']} not evaluated; report in {docs}")
    sys.stdout.flush()


def ints(s):
    return [int(x) for x in s.split(",") if x]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    p.add_argument("--out", default=None,
                   help="images and runs (not in git; default out/accuracy, with --quick out/accuracy-quick)")
    p.add_argument("--ref", default=os.path.join(ROOT, "out", "reference"), help="cached references (not in git)")
    p.add_argument("--docs", default=None,
                   help="tables and plots (default docs/accuracy; with --quick, or '', OUT/report and no document)")
    p.add_argument("--doc", default=os.path.join(ROOT, "docs", "ACCURACY.md"), help="document whose generated blocks are replaced")
    p.add_argument("--quick", action="store_true", help="smoke run: default scene, few points, weak reference, short curves")
    p.add_argument("--peers", action="store_true", help="also Blender Cycles and the Embree pathtracer probe")
    p.add_argument("--no-sweeps", dest="sweeps", action="store_false",
                   help="skip the parameter sweeps (a convergence-only run)")
    p.add_argument("--baseline-build", default="",
                   help="a previous build (folder with bin/igi-master, or bin/ itself): its first frame and "
                        "accumulation curve at the same settings, and the ratios new / old")
    p.add_argument("--references-only", action="store_true",
                   help="render (or find cached) the references of the chosen scenes, and stop")
    p.add_argument("--scenes", default="", help="comma-separated subset of: " + ", ".join(SCENE_NAMES))
    p.add_argument("--width", type=int, default=320)
    p.add_argument("--height", type=int, default=240)
    p.add_argument("--clients", type=int, default=2)
    p.add_argument("--seconds", type=float, default=None,
                   help="render time the accumulation and Cycles curves span (default 60; --quick 3)")
    p.add_argument("--min-frames", type=int, default=None, help="accumulated frames at least (default 256; --quick 16)")
    p.add_argument("--max-frames", type=int, default=20000, help="accumulated frames at most")
    p.add_argument("--ref-spp", type=int, default=None, help="reference spp per frame (default 64; --quick 16)")
    p.add_argument("--ref-frames", type=int, default=None,
                   help="reference frames, both halves together (default 256, i.e. 16384 spp, times the scene's "
                        "ref_factor; --quick 8)")
    p.add_argument("--first-frame-repeats", type=int, default=3, help="sessions per build for the first-frame comparison")
    p.add_argument("--first-frame-frames", type=int, default=16, help="frames of each of those sessions")
    p.add_argument("--command", default="scripts/bench_accuracy.sh", help="the command line recorded in the document")
    p.add_argument("--modes", default="",
                   help="a run of the GI modes instead (e.g. cache,photonmap): igi, each mode and our path tracer "
                        "accumulated per scene; writes docs/accuracy/modes-WxH/ and the block modes-WxH only")
    p.add_argument("--peer-rows", default=os.path.join(ROOT, "docs", "accuracy", "results.csv"),
                   help="with --modes: the main run's results.csv whose Cycles points join the Pareto front")
    a = p.parse_args()
    a.modes = [m for m in a.modes.split(",") if m]
    a.scenes = [s for s in a.scenes.split(",") if s]
    unknown = [s for s in a.scenes if s not in SCENE_NAMES]
    if unknown:
        p.error(f"unknown scene(s) {', '.join(unknown)}; known: {', '.join(SCENE_NAMES)}")
    a.baseline_bin = ""
    a.baseline_build = os.path.abspath(a.baseline_build) if a.baseline_build else ""
    if a.baseline_build:
        for cand in (os.path.join(a.baseline_build, "bin"), a.baseline_build):
            if all(os.access(os.path.join(cand, exe), os.X_OK) for exe in ("igi-master", "igi-client")):
                a.baseline_bin = cand
                break
        else:
            p.error(f"--baseline-build {a.baseline_build}: no bin/igi-master and bin/igi-client there")
    a.spf_frames, a.margin, a.cycles_max_spp = 4, 1.25, 65536
    if a.quick:
        a.scenes = a.scenes or ["default"]
        a.vpls, a.direct, a.photons, a.interleave = [6, 18, 54], [1, 4, 16], [0, 500], [1, 3]
        a.timing_frames = 2
        defaults = {"seconds": 3.0, "min_frames": 16, "ref_spp": 16, "ref_frames": 8}
    else:
        a.vpls, a.direct, a.photons, a.interleave = [2, 6, 18, 54, 162], [1, 2, 4, 8, 16], [0, 100, 500, 2000, 8000], [1, 2, 3, 4]
        a.timing_frames = 4
        defaults = {"seconds": 60.0, "min_frames": 256, "ref_spp": 64, "ref_frames": 256}
    for key, value in defaults.items():
        if getattr(a, key) is None:
            setattr(a, key, value)
    if a.ref_frames < 2 or a.ref_frames % 2:
        p.error("--ref-frames must be even (two halves)")
    if a.out is None and a.modes:
        a.out = os.path.join(ROOT, "out", f"accuracy-modes-{a.width}x{a.height}")
    if a.out is None:
        a.out = os.path.join(ROOT, "out", "accuracy-quick" if a.quick else "accuracy")
    if a.docs is None:
        a.docs = "" if a.quick else os.path.join(ROOT, "docs", "accuracy")
        if a.modes and not a.quick:
            a.docs = os.path.join(a.docs, f"modes-{a.width}x{a.height}")
    a.peer_rows, a.peer_note = load_peer_rows(a.peer_rows if a.modes else "", a.width, a.height, a.scenes)
    # Only a full-strength run is evidence for the claims: a reference of >= 4096 spp, curves of
    # >= 60 s and >= 256 frames. Anything less is reported as a smoke run.
    a.evidence = (not a.quick and a.ref_spp * a.ref_frames >= 4096 and a.seconds >= 60
                  and a.min_frames >= BIAS_FRAMES)
    started = machine()
    bench = Bench(a)
    bench.run_all()
    if a.references_only:
        for name, info in bench.refs.items():
            log(f"{name}: {bench.ref_images[name]}: {info['spp_total']} spp, {info['seconds']:.0f} s, "
                f"noise floor relMSE {info['noise_floor_relative_mse']:.3g}")
        return
    if not bench.rows:
        raise SystemExit("no scene was rendered")
    docs = a.docs if a.docs else os.path.join(a.out, "report")
    if a.modes:
        parts = write_modes_report(bench, docs, a.command, started)
        if a.docs and not a.quick:
            report_util.splice(a.doc, parts, log)
        log(f"wrote {docs}/results.md, results.csv, summary.json and plots")
        return
    parts, claims = write_reports(bench, docs, a.command, started)
    if a.docs and not a.quick:
        report_util.splice(a.doc, parts, log)
    log(f"wrote {docs}/results.md, results.csv, summary.json and plots")
    print_summary(claims, not a.evidence, docs)


if __name__ == "__main__":
    main()
