#!/usr/bin/python3
"""Issue 35's "Must show": the sun, spot lights and the sky against Blender Cycles and our path tracer.

For each scene (below) it renders, at --width x --height (160 x 120 by default), on the same cores:
  IGI          igi-master, --frames accumulated frames (256), one local client with --threads;
  path         igi-master --integrator path, --pt-spp per frame x --pt-frames frames (64 x 64 = 4096 spp);
  Cycles       scripts/peers/cycles_render.py, seed 1: --cycles-spp (256) samples per pixel;
  reference    Cycles again with seed 2 (independent of the images it judges), --ref-spp samples
               (1024 by default: what 2 shared cores render in the time; a scene may ask for
               fewer: its `ref_spp`);
and compares them with build/bin/igi-compare:
  ratio        mean(IGI) / mean(Cycles reference) over all pixels and channels (target |ratio - 1| <= 2 %);
  bias         mean(IGI) / mean(path) - 1 (target |bias| <= 0.5 %);
  relMSE       IGI's and Cycles' 256-spp image against the Cycles reference (target: IGI's <= 1.5 x
               Cycles'); the reference's own noise adds about relMSE(Cycles 256) x 256 / ref_spp to both.
For the scenes marked `curve` (the sunlit Sponza) also the trade: relMSE against render time for
IGI (the accumulated image after 1, 2, 4, ... frames; time = frames x the run's seconds per
frame, from --stats-json, as scripts/accuracy_report.py counts it) and for Cycles (renders of
1, 2, 4, ... spp until one takes --seconds of CPU time per thread, time = bpy.ops.render.render's),
both against the
reference, compared at equal time by scripts/equal_time.py's log-log interpolation.

Writes under --out (build/lights_mustshow): every render and log (reused when present; --rerun
renders again). Writes under --docs (docs/lights): <scene>.png (IGI | Cycles reference |
difference), sponza-sunlit-time.png (the curves), results.csv (every point, in
accuracy_report.py's columns), results.json (the figures), and replaces the block between the
`BEGIN GENERATED mustshow` and `END GENERATED mustshow` markers of docs/LIGHTS.md.

With --variants, each scene's lights are also rendered one at a time (each light alone, the
environment alone), as scripts/lights_cycles.sh does, to tell which light a miss comes from.

Run it through scripts/lights_mustshow.sh (installs Blender, numpy, matplotlib, OpenImageIO's
Python module and tools, builds). Everything heavy runs under nice -n 19.
"""

import argparse
import csv
import json
import math
import os
import resource
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from equal_time import at as loglog_at  # noqa: E402
from light_variants import write_variants  # noqa: E402

SCENES = [
    {"name": "cornell-spot", "file": "scenes/cornell/spot.json",
     "what": "our Cornell room with a diffuse box, lit by one spot light alone (scenes/cornell/spot.json)"},
    {"name": "sponza-sunlit", "file": "scenes/sponza/sunlit.json", "curve": True,
     "what": "Dabrovic Sponza lit by a sun (0.53 degrees) through the atrium and a constant sky "
             "(scenes/sponza/sunlit.json)"},
    {"name": "spheres-studio", "file": "scenes/sky/spheres-studio.json",
     "what": "Khronos MetalRoughSpheresNoTextures (glTF) under ../shared/scenes/hdri/studio.exr"},
    {"name": "spheres-courtyard", "file": "scenes/sky/spheres-courtyard.json",
     "what": "Khronos MetalRoughSpheresNoTextures (glTF) under ../shared/scenes/hdri/courtyard.exr"},
]

BEGIN = "<!-- BEGIN GENERATED mustshow (scripts/lights_mustshow.sh) -->"
END = "<!-- END GENERATED mustshow -->"


def log(msg):
    print(f"[mustshow {time.strftime('%H:%M:%S')}] {msg}", flush=True)


class Runner:
    def __init__(self, a):
        self.a = a
        self.bin = os.path.join(a.build, "bin")
        os.makedirs(a.out, exist_ok=True)

    def run(self, cmd, logfile):
        """Runs cmd under nice; returns (wall seconds, CPU seconds of it and its children)."""
        t0 = time.time()
        r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        with open(logfile, "w") as f:
            p = subprocess.run(["nice", "-n", "19", *cmd], stdout=f, stderr=subprocess.STDOUT)
        r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        if p.returncode != 0:
            with open(logfile) as f:
                tail = f.read()[-3000:]
            raise SystemExit(f"failed ({p.returncode}): {' '.join(cmd)}\n{tail}")
        return time.time() - t0, (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)

    def fresh(self, path):
        return self.a.rerun or not os.path.exists(path)

    def master(self, scene, out_exr, frames, extra, sequence_frames=None):
        """One igi-master session; returns its --stats-json."""
        stats = out_exr.replace(".exr", "-stats.json")
        while os.path.exists(out_exr + ".running") and not os.path.exists(stats):
            time.sleep(10)  # the same render, started by hand beside this run: wait for it
        if self.fresh(out_exr) or not os.path.exists(stats):
            cmd = [os.path.join(self.bin, "igi-master"), "--scene", scene, "--allow-outside-paths",
                   "--local-clients", "1", "--client-threads", str(self.a.threads), "--width", str(self.a.width),
                   "--height", str(self.a.height), "--frames", str(frames), "--output", out_exr,
                   "--stats-json", stats, "--listen", "127.0.0.1:0", "--log-level", "warn", *extra]
            if sequence_frames:
                seq = out_exr.replace(".exr", "-%04d.exr")
                cmd += ["--output-sequence", seq, "--sequence-frames", ",".join(str(k - 1) for k in sequence_frames)]
            log(f"  igi-master {' '.join(extra) or 'igi'}: {frames} frames -> {os.path.basename(out_exr)}")
            wall, cpu = self.run(cmd, out_exr.replace(".exr", ".log"))
            log(f"    {wall:.0f} s wall, {cpu:.0f} s CPU")
            with open(out_exr.replace(".exr", "-cpu.json"), "w") as f:
                json.dump({"wall_seconds": wall, "cpu_seconds": cpu}, f)
        with open(stats) as f:
            st = json.load(f)
        cpu_file = out_exr.replace(".exr", "-cpu.json")
        if os.path.exists(cpu_file):
            with open(cpu_file) as f:
                st["cpu"] = json.load(f)
        return st

    def cycles(self, scene, prefix, spps, seed, until=None):
        """One Blender session; returns its JSON (render seconds of each sample count)."""
        meta = prefix + ".json"
        want = [f"{prefix}-{s}spp.exr" for s in spps]
        if self.fresh(meta) or not all(os.path.exists(w) for w in want):
            cmd = ["blender", "-b", "--factory-startup", "-noaudio", "-P",
                   os.path.join(ROOT, "scripts", "peers", "cycles_render.py"), "--", scene, prefix,
                   str(self.a.width), str(self.a.height), str(self.a.threads), *[str(s) for s in spps],
                   "--seed", str(seed)]
            if until:
                # Until one render has taken --seconds of CPU time per thread: the wall time of a
                # shared machine says more about its other users than about Cycles.
                cmd += ["--until-cpu", str(until), "--max-spp", str(self.a.cycles_max_spp)]
            log(f"  Cycles seed {seed}: {' '.join(str(s) for s in spps)} spp{' until ' + str(until) + ' s' if until else ''}")
            wall, cpu = self.run(cmd, prefix + ".log")
            log(f"    {wall:.0f} s wall, {cpu:.0f} s CPU")
        with open(meta) as f:
            return json.load(f)

    def compare(self, image, reference):
        p = subprocess.run([os.path.join(self.bin, "igi-compare"), image, reference], capture_output=True,
                           text=True, check=True)
        return json.loads(p.stdout)


def sun_paths(r, scene_path, out_json):
    """scripts/peers/sun_paths.py: where the sun's light paths land (geometry only)."""
    if r.fresh(out_json):
        log("  sun_paths.py: the sun's light paths against what the camera sees")
        p = subprocess.run(["nice", "-n", "19", "blender", "-b", "--factory-startup", "-noaudio", "-P",
                            os.path.join(ROOT, "scripts", "peers", "sun_paths.py"), "--", scene_path, "4096", "400"],
                           capture_output=True, text=True)
        line = next((l for l in p.stdout.splitlines() if l.startswith("SUNPATHS ")), None)
        if line is None:
            log("    sun_paths.py failed: " + (p.stdout + p.stderr)[-500:])
            return None
        with open(out_json, "w") as f:
            f.write(line[len("SUNPATHS "):])
    with open(out_json) as f:
        found = json.load(f)
    found["scene"] = os.path.relpath(found["scene"], ROOT)
    return found


def frame_counts(n):
    """1, 2, 4, ... below n, and n (as accuracy_report.py keeps them)."""
    ks, k = [], 1
    while k < n:
        ks.append(k)
        k *= 2
    return ks + [n]


def variant_files(scene_path, out_dir):
    """Copies of a scene with one light source each, in out_dir (paths made relative to it:
    --allow-outside-paths takes relative paths only)."""
    spec = json.load(open(scene_path))
    folder = os.path.dirname(os.path.abspath(scene_path))

    def moved(p):
        return os.path.relpath(os.path.normpath(os.path.join(folder, p)), out_dir)

    for m in spec.get("meshes", []):
        m["file"] = moved(m["file"])
    if "file" in spec.get("environment", {}):
        spec["environment"]["file"] = moved(spec["environment"]["file"])
    base = os.path.splitext(os.path.basename(scene_path))[0]
    return write_variants(spec, out_dir, base)


def read_rgb(path):
    import OpenImageIO as oiio

    buf = oiio.ImageBuf(path)
    px = buf.get_pixels(oiio.FLOAT)
    if px is None:
        raise SystemExit(f"cannot read {path}")
    return px[..., :3]


def luminance(img):
    return 0.2126 * img[..., 0] + 0.7152 * img[..., 1] + 0.0722 * img[..., 2]


def side_by_side(ours, theirs, out_png, labels, zoom=2):
    """IGI | Cycles | signed difference of luminance over the reference's mean, at `zoom` x."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    a, b = read_rgb(ours), read_rgb(theirs)
    mean = float(luminance(b).mean())
    key = 0.25 / max(mean, 1e-12)

    def tone(img):
        x = np.clip(img * key, 0.0, None)
        x = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)
        return np.clip(x, 0, 1)

    diff = (luminance(a) - luminance(b)) / max(mean, 1e-12)
    h, w = b.shape[:2]
    fig, axes = plt.subplots(1, 3, figsize=(3 * w * zoom / 100, h * zoom / 100 + 0.5), dpi=100)
    for ax, img, title in ((axes[0], tone(a), labels[0]), (axes[1], tone(b), labels[1])):
        ax.imshow(img, interpolation="nearest")
        ax.set_title(title, fontsize=8)
    im = axes[2].imshow(diff, cmap="RdBu_r", vmin=-0.5, vmax=0.5, interpolation="nearest")
    axes[2].set_title("(IGI - Cycles) / mean(Cycles): -50 % blue .. +50 % red", fontsize=7)
    for ax in axes:
        ax.set_xticks([])
        ax.set_yticks([])
    fig.tight_layout(pad=0.3)
    fig.savefig(out_png)
    plt.close(fig)


def time_plot(points, out_png, title, floor, threads):
    """Two panels: relMSE against wall time, and against CPU seconds / threads."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(12, 4.6))
    for ax, col, xlabel in ((axes[0], 1, "wall seconds of the render (log)"),
                            (axes[1], 2, f"CPU seconds / {threads}: the time on {threads} cores of its own (log)")):
        for renderer, style in (("igi", "o-"), ("cycles", "s-")):
            pts = sorted((p[col], p[3]) for p in points if p[0] == renderer)
            if pts:
                ax.plot([p[0] for p in pts], [p[1] for p in pts], style, ms=4,
                        label="IGI, accumulated frames" if renderer == "igi" else "Cycles, spp doubling")
        if floor:
            ax.axhline(floor, color="k", lw=0.8, alpha=0.6, label="reference's own noise (estimate)")
        ax.axvline(1, color="k", lw=0.5, ls=":")
        ax.axvline(60, color="k", lw=0.5, ls=":")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(xlabel, fontsize=8)
        ax.set_ylabel("relMSE against Cycles' reference (log)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(title, fontsize=9)
    fig.tight_layout()
    fig.savefig(out_png, dpi=100)
    plt.close(fig)


def equal_time(points, col):
    igi_pts = sorted((p[col], p[3]) for p in points if p[0] == "igi")
    cyc_pts = sorted((p[col], p[3]) for p in points if p[0] == "cycles")
    equal = []
    for t in (1, 2, 5, 10, 20, 30, 60):
        ei, ec = loglog_at(igi_pts, t), loglog_at(cyc_pts, t)
        equal.append({"seconds": t, "igi": ei, "cycles": ec, "cycles_over_igi": ec / ei if ei and ec else None})
    return equal


# ------------------------------------------------------------------ one scene
def render_scene(r, sc, scene_path, tag, curve, results, rows):
    a = r.a
    out = os.path.join(a.out, tag)
    os.makedirs(out, exist_ok=True)
    res = {"scene": tag, "file": os.path.relpath(scene_path, ROOT)}
    ref_spp = min(a.ref_spp, sc.get("ref_spp", a.ref_spp))
    log(f"{tag}: {scene_path}")

    # Cycles: the 256-spp image (and the curve) with seed 1, the reference with seed 2.
    spps = [a.cycles_spp]
    if curve:
        spps = sorted(set(frame_counts(a.cycles_spp)))
    cyc = r.cycles(scene_path, os.path.join(out, "cycles"), spps, 1, until=a.seconds if curve else None)
    ref_meta = r.cycles(scene_path, os.path.join(out, "cycles-ref"), [ref_spp], 2)
    ref = os.path.join(out, f"cycles-ref-{ref_spp}spp.exr")
    res["ref_spp"] = ref_spp
    res["ref_seconds"] = ref_meta["renders"][-1]["seconds"]
    cyc_img = os.path.join(out, f"cycles-{a.cycles_spp}spp.exr")
    if a.cycles_only:
        return res

    # IGI and the path tracer.
    igi = os.path.join(out, "igi.exr")
    st = r.master(scene_path, igi, a.frames, [], sequence_frames=frame_counts(a.frames) if curve else None)
    res["igi_seconds"] = st["seconds"]
    res["igi_frames"] = len(st["frames"])
    vpls = [f["vpls"] for f in st["frames"]]
    res["vpls_per_set"] = sum(vpls) / max(1, len(vpls))
    pt = os.path.join(out, "path.exr")
    pst = r.master(scene_path, pt, a.pt_frames, ["--integrator", "path", "--spp", str(a.pt_spp)])
    res["path_spp"] = a.pt_spp * len(pst["frames"])
    res["path_seconds"] = pst["seconds"]

    c_igi = r.compare(igi, ref)
    c_cyc = r.compare(cyc_img, ref)
    c_bias = r.compare(igi, pt)
    c_pt = r.compare(pt, ref)
    res.update(
        ratio_igi_cycles=1 + c_igi["mean_relative_bias"],
        ratio_path_cycles=1 + c_pt["mean_relative_bias"],
        ratio_cycles256_cycles=1 + c_cyc["mean_relative_bias"],
        bias_igi_path=c_bias["mean_relative_bias"],
        relmse_igi=c_igi["relative_mse"],
        relmse_cycles=c_cyc["relative_mse"],
        relmse_igi_path=c_bias["relative_mse"],
        relmse_path_cycles=c_pt["relative_mse"],
        ssim_igi=c_igi["ssim"],
        ssim_cycles=c_cyc["ssim"],
        cycles_seconds=next(x["seconds"] for x in cyc["renders"] if x["spp"] == a.cycles_spp),
    )
    res["relmse_ratio"] = res["relmse_igi"] / res["relmse_cycles"] if res["relmse_cycles"] > 0 else float("inf")
    # relMSE ~ 1 / spp for Cycles: its reference carries about this much of its own.
    res["ref_noise_relmse"] = res["relmse_cycles"] * a.cycles_spp / ref_spp
    res["targets"] = {
        "ratio": abs(res["ratio_igi_cycles"] - 1) <= 0.02,
        "bias": abs(res["bias_igi_path"]) <= 0.005,
        "relmse": res["relmse_ratio"] <= 1.5,
    }
    log(f"  IGI/Cycles {res['ratio_igi_cycles']:.4f}, path/Cycles {res['ratio_path_cycles']:.4f}, "
        f"IGI/path - 1 {res['bias_igi_path']:+.4f}, relMSE IGI {res['relmse_igi']:.4g} vs Cycles "
        f"{a.cycles_spp} spp {res['relmse_cycles']:.4g} ({res['relmse_ratio']:.2f}x)")

    for renderer, frames, time_s, image in (("igi", a.frames, st["seconds"], igi),
                                            ("cycles", a.cycles_spp, res["cycles_seconds"], cyc_img),
                                            ("path", res["path_spp"], pst["seconds"], pt)):
        c = {"igi": c_igi, "cycles": c_cyc, "path": c_pt}[renderer]
        rows.append({"scene": tag, "renderer": renderer, "sweep": "frames" if renderer != "cycles" else "spp",
                     "value": frames, "frames": frames, "time": time_s, "relmse": c["relative_mse"],
                     "ssim": c["ssim"], "bias": c["mean_relative_bias"], "reference": f"cycles-{ref_spp}spp-seed2"})

    if curve:
        # Time two ways: wall seconds (what the renderers report: IGI's --stats-json seconds,
        # Cycles' bpy.ops.render.render) and CPU seconds / threads (Cycles': its process's CPU
        # time over each render; IGI's: the session's CPU time, master and client, in the share
        # of the session's wall time its frames took), which the other users of a shared
        # machine change less.
        def per_frame(stats):
            n = max(1, len(stats["frames"]))
            wall = stats["seconds"] / n
            cpu = stats.get("cpu")
            norm = cpu["cpu_seconds"] * (stats["seconds"] / cpu["wall_seconds"]) / a.threads / n if cpu else None
            return wall, norm

        points = []
        spf, spf_cpu = per_frame(st)
        if (spf_cpu or spf) * len(st["frames"]) < a.seconds:
            # The 256 frames took less than --seconds (CPU seconds per thread where known: the
            # wall time of a shared machine runs ahead of them): a longer run for the curve.
            n = math.ceil(a.seconds * 1.15 / (spf_cpu or spf))
            long = os.path.join(out, "igi-long.exr")
            lst = r.master(scene_path, long, n, [], sequence_frames=frame_counts(n))
            spf, spf_cpu = per_frame(lst)
            seq, ks = long.replace(".exr", "-%04d.exr"), frame_counts(n)
            res["igi_curve_frames"] = n
        else:
            seq, ks = igi.replace(".exr", "-%04d.exr"), frame_counts(a.frames)
            res["igi_curve_frames"] = a.frames
        res["igi_seconds_per_frame"] = spf
        res["igi_cpu_seconds_per_frame"] = spf_cpu
        for k in ks:
            c = r.compare(seq % (k - 1), ref)
            points.append(("igi", spf * k, (spf_cpu or float("nan")) * k, c["relative_mse"]))
            rows.append({"scene": tag, "renderer": "igi", "sweep": "curve", "value": k, "frames": k,
                         "time": spf * k, "relmse": c["relative_mse"], "ssim": c["ssim"],
                         "bias": c["mean_relative_bias"], "reference": f"cycles-{ref_spp}spp-seed2"})
        for x in cyc["renders"]:
            c = r.compare(x["image"], ref)
            points.append(("cycles", x["seconds"], x.get("cpu_seconds", float("nan")) / a.threads,
                           c["relative_mse"]))
            rows.append({"scene": tag, "renderer": "cycles", "sweep": "curve", "value": x["spp"], "frames": 1,
                         "time": x["seconds"], "relmse": c["relative_mse"], "ssim": c["ssim"],
                         "bias": c["mean_relative_bias"], "reference": f"cycles-{ref_spp}spp-seed2"})
        res["equal_time"] = equal_time(points, 1)
        res["equal_cpu_time"] = equal_time(points, 2)
        res["curve_points"] = points
        if a.docs:
            time_plot(points, os.path.join(a.docs, f"{tag}-time.png"),
                      f"{tag}, {a.width} x {a.height}: relMSE against Cycles {ref_spp} spp (seed 2), "
                      f"{a.threads} threads each", res["ref_noise_relmse"], a.threads)
    if curve:
        res["sun_paths"] = sun_paths(r, scene_path, os.path.join(out, "sun-paths.json"))
        # A miss of the relMSE target, looked into: the same accumulation without the
        # discontinuity buffer (its 3 x 3 blur of the filtered irradiance across sharp sun
        # shadows is what the progressive filter must withdraw, frame by frame).
        diag = {}
        for label, extra in (("filter 1x1", ["--filter", "1x1"]),):
            img = os.path.join(out, "igi-" + label.replace(" ", "-") + ".exr")
            dst = r.master(scene_path, img, a.frames, extra)
            c, cp = r.compare(img, ref), r.compare(img, pt)
            diag[label] = {"flags": " ".join(extra), "ratio_igi_cycles": 1 + c["mean_relative_bias"],
                           "relmse_igi": c["relative_mse"], "bias_igi_path": cp["mean_relative_bias"],
                           "relmse_igi_path": cp["relative_mse"], "seconds": dst["seconds"]}
            log(f"  IGI {' '.join(extra)}: IGI/Cycles {diag[label]['ratio_igi_cycles']:.4f}, relMSE "
                f"{c['relative_mse']:.4g}, IGI/path - 1 {cp['mean_relative_bias']:+.4f}")
        res["diagnostics"] = diag
    if a.docs:
        side_by_side(igi, ref, os.path.join(a.docs, f"{tag}.png"),
                     (f"IGI, {a.frames} frames", f"Cycles, {ref_spp} spp"))
    results[tag] = res
    return res


# ------------------------------------------------------------------ report
def pct(x):
    return f"{100 * x:+.2f} %"


def ok(b):
    return "yes" if b else "**no**"


def markdown(results, a, command, started, seconds):
    lines = [BEGIN, "",
             f"Generated by `{command}` (this pass started {started} and took {seconds / 60:.0f} min; the "
             f"renders are kept in `{os.path.relpath(a.out, ROOT)}/` and reused, and the table of times "
             "below says what each took). "
             f"{a.width} x {a.height}; IGI {a.frames} accumulated frames; our path tracer "
             f"{a.pt_spp} spp x {a.pt_frames} frames; Cycles (Blender 3.4) {a.cycles_spp} spp with seed 1 and "
             f"its reference with seed 2 (independent of the images it judges); {a.threads} threads "
             "each, everything under `nice -n 19`, beside other people's builds and at times beside "
             "each other: wall times say as much about the machine's load as about the renderers (the "
             "curve below is therefore also drawn against CPU seconds per thread). Ratio: "
             "mean over all pixels and channels, image over reference (`igi-compare`'s "
             "`mean_relative_bias` + 1).", "",
             "| scene | IGI / Cycles ref (target within 2 %) | IGI / path - 1 (target within 0.5 %) | "
             "relMSE IGI / relMSE Cycles 256 spp (target <= 1.5) | path / Cycles ref | relMSE path, IGI against "
             "Cycles ref / against path | Cycles ref spp |",
             "|---|---|---|---|---|---|---|"]
    for tag, r in results.items():
        t = r["targets"]
        lines.append(
            f"| {tag} | {r['ratio_igi_cycles']:.4f} ({ok(t['ratio'])}) | {pct(r['bias_igi_path'])} "
            f"({ok(t['bias'])}) | {r['relmse_igi']:.3g} / {r['relmse_cycles']:.3g} = "
            f"{r['relmse_ratio']:.2f} ({ok(t['relmse'])}) | {r['ratio_path_cycles']:.4f} | "
            f"{r['relmse_path_cycles']:.3g}, {r['relmse_igi']:.3g} / {r['relmse_igi_path']:.3g} | {r['ref_spp']} |")
    lines += ["", "Time (seconds of rendering, as each renderer reports it):", "",
              "| scene | IGI, frames | our path tracer | Cycles 256 spp | Cycles reference | VPLs per set (stats) |",
              "|---|---|---|---|---|---|"]
    for tag, r in results.items():
        lines.append(f"| {tag} | {r['igi_seconds']:.1f} ({r['igi_frames']}) | {r['path_seconds']:.1f} "
                     f"({r['path_spp']} spp) | {r['cycles_seconds']:.1f} | {r['ref_seconds']:.1f} "
                     f"| {r['vpls_per_set']:.1f} |")
    lines += ["", "The reference's own noise, about relMSE(Cycles 256) x 256 / ref spp, is in both relMSE "
              "figures: " + ", ".join(f"{tag} {r['ref_noise_relmse']:.2g}" for tag, r in results.items()) + ".", ""]
    for tag, r in results.items():
        lines += [f"![{tag}: IGI, Cycles and their difference](lights/{tag}.png)", ""]
    for tag, r in results.items():
        if "equal_time" not in r:
            continue
        cpu_spf = r.get("igi_cpu_seconds_per_frame")
        lines += [f"**The trade on {tag}** (IGI's accumulation over {r['igi_curve_frames']} frames at "
                  f"{r['igi_seconds_per_frame']:.3g} wall s per frame"
                  + (f", {cpu_spf:.3g} CPU s / {a.threads} per frame" if cpu_spf else "")
                  + f"; Cycles doubling spp until a render takes {a.seconds:g} CPU s / {a.threads}), relMSE against the same "
                  "Cycles reference, at equal time (log-log interpolation, `scripts/equal_time.py`'s), by "
                  f"wall time and by CPU seconds / {a.threads}:", "",
                  f"![{tag}: relMSE against time](lights/{tag}-time.png)", "",
                  "| seconds | relMSE IGI (wall) | relMSE Cycles (wall) | Cycles / IGI (wall) | relMSE IGI (CPU) "
                  "| relMSE Cycles (CPU) | Cycles / IGI (CPU) |", "|---:|---:|---:|---:|---:|---:|---:|"]
        g = lambda x, spec=".3g": format(x, spec) if x else "-"
        for e, c in zip(r["equal_time"], r.get("equal_cpu_time", [{}] * 7)):
            lines.append(f"| {e['seconds']} | {g(e['igi'])} | {g(e['cycles'])} | {g(e['cycles_over_igi'], '.2f')} "
                         f"| {g(c.get('igi'))} | {g(c.get('cycles'))} | {g(c.get('cycles_over_igi'), '.2f')} |")
        lines.append("")
    for tag, r in results.items():
        for label, d in r.get("diagnostics", {}).items():
            lines += [f"Looking into {tag}: IGI ({a.frames} frames) with `{d['flags']}`: IGI / Cycles ref "
                      f"{d['ratio_igi_cycles']:.4f}, relMSE {d['relmse_igi']:.3g} (with the buffer "
                      f"{r['relmse_igi']:.3g}; Cycles {a.cycles_spp} spp {r['relmse_cycles']:.3g}), IGI / path - 1 "
                      f"{pct(d['bias_igi_path'])}, relMSE against our path tracer {d['relmse_igi_path']:.3g} "
                      f"(with the buffer {r['relmse_igi_path']:.3g}).", ""]
    for tag, r in results.items():
        sp = r.get("sun_paths")
        if not sp:
            continue
        for sun in sp["suns"]:
            n = sp["paths"]
            hit = n - sun["missed"]
            lines += [f"**Wasted light paths on {tag}** (`scripts/peers/sun_paths.py`, geometry only: {n} "
                      f"paths from the rectangle the scene's box fills across the sun `{sun['name']}`, as the renderer "
                      f"starts them; a VPL is useful when one of {sp['receivers_on_geometry']} points that camera "
                      "rays hit lies in front of it and sees it): "
                      f"{100 * sun['missed'] / n:.0f} % of the paths hit nothing, "
                      f"{100 * sun['first_wasted'] / n:.0f} % leave their first VPL where no visible point "
                      f"sees it (the roofs and outer walls), {100 * sun['first_useful'] / n:.1f} % leave a "
                      f"useful one; of the paths that hit, a cosine bounce from the first vertex escapes to "
                      f"the sky {100 * sun['second_missed'] / max(1, hit):.0f} % of the time and reaches a "
                      f"useful second VPL {100 * sun['second_useful'] / max(1, hit):.0f} %. "
                      f"IGI's statistics (`--stats-json`, `frames[].vpls`) give {r['vpls_per_set']:.1f} VPLs "
                      "per set on average for this scene: the paths that hit nothing make none, but a VPL "
                      "on a roof counts like any other.", ""]
    if any("variants" in r for r in results.values()):
        lines += ["Each light alone (the same renders per light source):", "",
                  "| scene | light | IGI / Cycles ref | IGI / path - 1 | path / Cycles ref | relMSE IGI / Cycles 256 |",
                  "|---|---|---|---|---|---|"]
        for tag, r in results.items():
            for label, v in r.get("variants", {}).items():
                lines.append(f"| {tag} | {label} | {v['ratio_igi_cycles']:.4f} | {pct(v['bias_igi_path'])} | "
                             f"{v['ratio_path_cycles']:.4f} | {v['relmse_ratio']:.2f} |")
        lines.append("")
    lines.append(END)
    return "\n".join(lines)


def common_args(ap, tag, scenes, width, height, ref_spp):
    """The options this script shares with scripts/materials_mustshow.py: renders under
    build/<tag>_mustshow, docs under docs/<tag>."""
    ap.add_argument("--build", default=os.path.join(ROOT, "build"), help="where bin/igi-master is")
    ap.add_argument("--out", default=os.path.join(ROOT, "build", f"{tag}_mustshow"))
    ap.add_argument("--docs", default=os.path.join(ROOT, "docs", tag))
    ap.add_argument("--width", type=int, default=width)
    ap.add_argument("--height", type=int, default=height)
    ap.add_argument("--frames", type=int, default=256)
    ap.add_argument("--pt-spp", type=int, default=64)
    ap.add_argument("--pt-frames", type=int, default=64)
    ap.add_argument("--cycles-spp", type=int, default=256)
    ap.add_argument("--ref-spp", type=int, default=ref_spp, help="a scene may ask for fewer (its ref_spp)")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--scenes", default=",".join(s["name"] for s in scenes))
    ap.add_argument("--rerun", action="store_true")
    ap.add_argument("--cycles-only", action="store_true",
                    help="render Cycles' images only (they need no build: run it while building), no report")
    ap.add_argument("--no-docs", action="store_true", help="print only; leave docs/ alone")


def parse(ap):
    a = ap.parse_args()
    a.out = os.path.abspath(a.out)
    if a.no_docs:
        a.docs = None
    else:
        os.makedirs(a.docs, exist_ok=True)
    return a


def write_results(docs, payload, rows):
    """docs/<tag>/results.json (the figures) and results.csv (every point, in
    accuracy_report.py's columns)."""
    with open(os.path.join(docs, "results.json"), "w") as f:
        json.dump(payload, f, indent=1)
    with open(os.path.join(docs, "results.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["scene", "renderer", "sweep", "value", "frames", "time", "relmse",
                                          "ssim", "bias", "reference"])
        w.writeheader()
        w.writerows(rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    common_args(ap, "lights", SCENES, 160, 120, 1024)
    ap.add_argument("--cycles-max-spp", type=int, default=16384)
    ap.add_argument("--seconds", type=float, default=60)
    ap.add_argument("--variants", action="store_true")
    ap.add_argument("--no-curve", action="store_true", help="no relMSE-against-time curve (and no sun_paths.py)")
    a = parse(ap)
    started, t0 = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), time.time()
    r = Runner(a)
    wanted = a.scenes.split(",")
    results, rows = {}, []
    for sc in SCENES:
        if sc["name"] not in wanted:
            continue
        path = os.path.join(ROOT, sc["file"])
        res = render_scene(r, sc, path, sc["name"], sc.get("curve", False) and not a.no_curve, results, rows)
        res["what"] = sc["what"]
        if a.cycles_only:
            continue
        if a.variants:
            vdir = os.path.join(a.out, sc["name"], "variants")
            os.makedirs(vdir, exist_ok=True)
            res["variants"] = {}
            for label, vpath in variant_files(path, vdir):
                vres = render_scene(r, sc, vpath, f"{sc['name']}.only-{label}", False, {}, rows)
                res["variants"][label] = vres
        # Written after every scene: a partial run leaves what it has.
        if a.docs:
            write_docs(a, results, rows, started, t0)
    if a.cycles_only:
        return
    print()
    for tag, x in results.items():
        print(f"{tag:20s} IGI/Cycles {x['ratio_igi_cycles']:.4f}  IGI/path-1 {x['bias_igi_path']:+.4f}  "
              f"relMSE IGI {x['relmse_igi']:.3g} Cycles256 {x['relmse_cycles']:.3g} ({x['relmse_ratio']:.2f}x)  "
              f"path/Cycles {x['ratio_path_cycles']:.4f}")
        for label, v in x.get("variants", {}).items():
            print(f"  only {label:14s} IGI/Cycles {v['ratio_igi_cycles']:.4f}  IGI/path-1 {v['bias_igi_path']:+.4f}  "
                  f"path/Cycles {v['ratio_path_cycles']:.4f}")
    print(f"total {(time.time() - t0) / 60:.1f} min")


def write_docs(a, results, rows, started, t0):
    write_results(a.docs, results, rows)
    command = "scripts/lights_mustshow.sh" + (" " + " ".join(sys.argv[1:]) if sys.argv[1:] else "")
    block = markdown(results, a, command, started, time.time() - t0)
    doc = os.path.join(ROOT, "docs", "LIGHTS.md")
    text = open(doc).read()
    if BEGIN in text and END in text:
        head, rest = text.split(BEGIN, 1)
        _, tail = rest.split(END, 1)
        text = head + block + tail
        with open(doc, "w") as f:
            f.write(text)
    else:
        with open(os.path.join(a.docs, "results.md"), "w") as f:
            f.write(block + "\n")
        log("docs/LIGHTS.md has no generated block: wrote docs/lights/results.md")


if __name__ == "__main__":
    main()
