#!/usr/bin/python3
"""Many lights: light samples and VPLs chosen by power against choosing them per point
(docs/PERFORMANCE.md, section "Many lights").

Run through scripts/bench_many_lights.sh (which installs and builds first). For each scene of
--scenes (default: the interior lit by 96 small ceiling lights, all diffuse and all glossy, the
same room with 133,000 triangles of ceramic pieces added, scenes/interior/sculptures.json, and
the Sponza atrium with the bunny and 120 small lights under its arcades,
scenes/sponza/arcades.json, whose meshes come from ../shared/scenes):
  1. a reference: our path tracer with the light tree, --ref-spp paths per pixel (16 per frame,
     accumulated; more for the scenes of MIN_REF_SPP), cached in
     --out/reference/<scene>-<W>x<H>-<spp>spp-<hash of the scene's files>.exr and reused;
  2. every variant: IGI with `--light-sampling power --vpl-sampling all` (the paper's choice:
     the same distribution for every point, every VPL of the set), with `tree` light samples,
     and with `tree` light samples and VPLs by importance (`--vpl-sampling importance`, a pool
     of 8 x 18 VPLs per set, 18 per point); our path tracer (16 spp a frame) with each light
     sampling.
     Each renders --frames frame counts (IGI: 1, 4, 16, 64 accumulated frames; the path tracer
     1 and 4 frames) for every seed of --seeds, one local client with all cores;
  3. each image against the reference with igi-compare: relMSE, bias, SSIM and speckle (the
     share of pixels brighter than 4 x the reference's at the same pixel, pixels darker than 1 %
     of its mean left out); time is the session's render time (--stats-json "seconds": from
     every client ready to the last frame composited); the mean over the seeds;
  4. at equal time: each variant's relMSE interpolated (log-log, piecewise linear) at the time
     power took for 16 frames; at equal error: the time each variant needs to reach power's
     16-frame relMSE (extrapolated along its last segment when it reaches it later than its
     last measurement; marked so);
  5. docs/perf/many-lights.json, docs/perf/many-lights.png and the block between
     "<!-- BEGIN GENERATED many-lights -->" and "<!-- END GENERATED many-lights -->" of
     docs/PERFORMANCE.md (the prose around it is kept).

Python 3 standard library plus matplotlib (Debian's python3-matplotlib, /usr/bin/python3).
"""

import argparse
import hashlib
import json
import math
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from report_util import machine, num, run, splice  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))

SCENES = {
    "interior-diffuse": ("scenes/interior/diffuse.json", ["scenes/interior/room.obj",
                                                          "scenes/interior/room.mtl"]),
    "interior-glossy": ("scenes/interior/glossy.json", ["scenes/interior/room.obj",
                                                        "scenes/interior/room.mtl"]),
    "sculptures": ("scenes/interior/sculptures.json", ["scenes/interior/room.obj",
                                                       "scenes/interior/room.mtl",
                                                       "scenes/interior/sculptures.obj",
                                                       "scenes/interior/sculptures.mtl"]),
    # Sponza with the bunny and 120 small lights under the arcades' vaults
    # (scripts/make_sponza_scene.py): the meshes come from ../shared/scenes.
    "sponza-arcades": ("scenes/sponza/arcades.json",
                       ["../shared/scenes/sponza-dabrovic/sponza.obj",
                        "../shared/scenes/sponza-dabrovic/sponza.mtl",
                        "../shared/scenes/stanford-bunny/bunny.obj"]),
}

# Scenes whose reference needs more paths than --ref-spp: their many small lights leave the path
# tracer's image noisy, and the reference's own noise is a floor under every relMSE.
MIN_REF_SPP = {"sponza-arcades": 4096}

# name: (integrator, extra igi-master arguments, frame counts)
VARIANTS = {
    # The paper's choices (and this project's before issue 17): light samples by power, every
    # point connected to every VPL of its set.
    "igi-power": ("igi", ["--light-sampling", "power", "--vpl-sampling", "all"], [1, 4, 16, 64]),
    # Light samples by the light tree, every VPL.
    "igi-tree": ("igi", ["--light-sampling", "tree", "--vpl-sampling", "all"], [1, 4, 16, 64]),
    # Light samples by the tree and VPLs by importance from a pool: the default from 8 emitters on.
    "igi-importance": ("igi", ["--light-sampling", "tree", "--vpl-sampling", "importance"],
                       [1, 4, 16, 64]),
    "path-power": ("path", ["--light-sampling", "power", "--spp", "16"], [1, 4]),
    "path-tree": ("path", ["--light-sampling", "tree", "--spp", "16"], [1, 4]),
}


def log(msg):
    print(msg, flush=True)


def scene_hash(files):
    h = hashlib.sha256()
    for f in files:
        with open(os.path.join(ROOT, f), "rb") as fh:
            h.update(fh.read())
    return h.hexdigest()[:8]


def master(build, scene, out, stats, args, width, height):
    cmd = [os.path.join(build, "bin", "igi-master"), "--scene", os.path.join(ROOT, scene),
           "--allow-outside-paths", "--local-clients", "1", "--width", str(width), "--height", str(height),
           "--output", out, "--stats-json", stats] + args
    run(cmd)
    with open(stats, encoding="utf-8") as f:
        return json.load(f)["seconds"]


def compare(build, image, reference):
    proc, _ = run([os.path.join(build, "bin", "igi-compare"), image, reference])
    return json.loads(proc.stdout)


def reference(build, name, out_dir, spp, width, height):
    scene, files = SCENES[name]
    path = os.path.join(out_dir, "reference",
                        f"{name}-{width}x{height}-{spp}spp-{scene_hash([scene] + files)}.exr")
    if os.path.exists(path):
        log(f"{name}: reference {path} (cached)")
        return path
    os.makedirs(os.path.dirname(path), exist_ok=True)
    frames = max(1, spp // 16)
    log(f"{name}: rendering the reference, {frames * 16} spp ...")
    t0 = time.time()
    master(build, scene, path, path + ".stats.json",
           ["--integrator", "path", "--light-sampling", "tree", "--spp", "16", "--frames",
            str(frames), "--seed", "1001"], width, height)
    log(f"  done in {time.time() - t0:.0f} s")
    return path


def interpolate(points, x):
    """log-log piecewise-linear y at x through points [(x, y)] sorted by x; extrapolates along
    the end segments."""
    pts = [(math.log(a), math.log(b)) for a, b in points if a > 0 and b > 0]
    if len(pts) < 2:
        return None
    lx = math.log(x)
    for i in range(len(pts) - 1):
        (x0, y0), (x1, y1) = pts[i], pts[i + 1]
        if lx <= x1 or i == len(pts) - 2:
            t = (lx - x0) / (x1 - x0) if x1 != x0 else 0.0
            return math.exp(y0 + t * (y1 - y0))
    return None


def time_to_reach(points, target):
    """Time at which the log-log curve through points [(seconds, relMSE)] reaches `target`, and a
    note: "extrapolated" past the last point, "at most" when the first point is already below."""
    pts = [(math.log(a), math.log(b)) for a, b in points if a > 0 and b > 0]
    if not pts:
        return None, "never"
    lt = math.log(target)
    if pts[0][1] <= lt:
        return math.exp(pts[0][0]), "at most"  # reached by the first measurement already
    for i in range(len(pts) - 1):
        (x0, y0), (x1, y1) = pts[i], pts[i + 1]
        if y1 <= lt or i == len(pts) - 2:
            if y1 == y0:
                return None, "never"
            t = (lt - y0) / (y1 - y0)
            return math.exp(x0 + t * (x1 - x0)), "extrapolated" if y1 > lt else ""
    return None, "never"


def measure(args):
    results = {}
    for name in args.scenes:
        scene, _ = SCENES[name]
        ref = reference(args.build, name, args.out, max(args.ref_spp, MIN_REF_SPP.get(name, 0)),
                        args.width, args.height)
        results[name] = {}
        for variant in args.variants:
            integrator, extra, frame_counts = VARIANTS[variant]
            rows = []
            for frames in frame_counts:
                per_seed = []
                for seed in args.seeds:
                    tag = f"{name}-{variant}-{frames}-s{seed}"
                    image = os.path.join(args.out, "runs", tag + ".exr")
                    os.makedirs(os.path.dirname(image), exist_ok=True)
                    seconds = master(args.build, scene, image, image + ".stats.json",
                                     ["--integrator", integrator, "--frames", str(frames),
                                      "--seed", str(seed)] + extra, args.width, args.height)
                    err = compare(args.build, image, ref)
                    per_seed.append({"seconds": seconds, "relmse": err["relative_mse"],
                                     "bias": err["mean_relative_bias"], "ssim": err["ssim"],
                                     "speckle": err.get("speckle")})
                mean = {k: sum(r[k] for r in per_seed) / len(per_seed) for k in per_seed[0]}
                mean["frames"] = frames
                rows.append(mean)
                log(f"{name} {variant} {frames:3d} frames: {mean['seconds']:.3f} s, relMSE "
                    f"{mean['relmse']:.4g}, bias {mean['bias']:+.4f}, speckle {mean['speckle']:.3g}")
            results[name][variant] = rows
    return results


def summarize(results):
    """Each variant against power sampling with the same integrator: IGI's at 16 frames, the
    path tracer's at its longest run (in a --quick run, power's longest run up to 16 frames)."""
    summary = {}
    for name, variants in results.items():
        s = {}
        for v, rows in variants.items():
            integrator = v.split("-")[0]
            power = variants.get(f"{integrator}-power")
            if not power:
                continue
            anchor = max((r for r in power if r["frames"] <= 16), key=lambda r: r["frames"])
            pts = sorted((r["seconds"], r["relmse"]) for r in rows)
            one = next((r for r in rows if r["frames"] == 1), None)
            at = interpolate(pts, anchor["seconds"])
            reach, extrapolated = time_to_reach(pts, anchor["relmse"])
            s[v] = {"anchor": f"{integrator}-power, {anchor['frames']} frames",
                    "anchor_seconds": anchor["seconds"], "anchor_relmse": anchor["relmse"],
                    "relmse_at_anchor_time": at,
                    "error_ratio_power_over_this": anchor["relmse"] / at if at else None,
                    "seconds_to_anchor_error": reach, "extrapolated": extrapolated,
                    # A lower bound when the time is an upper one ("at most").
                    "speedup_at_anchor_error": anchor["seconds"] / reach if reach else None,
                    "speckle_1": one["speckle"] if one else None,
                    "seconds_per_frame_1": one["seconds"] if one else None}
        summary[name] = s
    return summary


def plot(results, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(results), figsize=(5 * len(results), 4), squeeze=False)
    for ax, (name, variants) in zip(axes[0], results.items()):
        for v, rows in variants.items():
            pts = sorted((r["seconds"], r["relmse"]) for r in rows)
            ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-" if "igi" in v else "s--",
                      label=v)
        ax.set_title(name)
        ax.set_xlabel("seconds (render time, one client, 2 threads)")
        ax.set_ylabel("relMSE against the reference")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=90)


def build_identity():
    """The commit measured, and whether the tree had uncommitted changes."""
    try:
        head, _ = run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"])
        dirty, _ = run(["git", "-C", ROOT, "status", "--porcelain", "--untracked-files=no"])
        n = len([l for l in dirty.stdout.splitlines() if l.strip()])
        return head.stdout.strip() + (f" with {n} uncommitted files" if n else "")
    except (RuntimeError, OSError):
        return "unknown"


def markdown(args, results, summary, env, wall):
    lines = [f"Measured on {env['date']} by `{args.command}` ({wall / 60:.0f} min), build "
             f"`{build_identity()}`, on "
             f"{env['cpu']} (`nproc` = {env['nproc']}), load average at the start "
             f"`{env['load']}`; {args.width} x {args.height}, one local client with every core, "
             f"seeds {','.join(map(str, args.seeds))} (means), references: our path tracer with "
             f"the light tree at {args.ref_spp} spp"
             + "".join(f" ({s}: {n})" for s, n in MIN_REF_SPP.items()
                       if s in results and n > args.ref_spp) + ".", "",
             "| scene | variant | frames | s | relMSE | bias | SSIM | speckle |",
             "|---|---|---:|---:|---:|---:|---:|---:|"]
    for name, variants in results.items():
        for v, rows in variants.items():
            for r in rows:
                lines.append(f"| {name} | {v} | {r['frames']} | {r['seconds']:.3f} | "
                             f"{num(r['relmse'])} | {r['bias'] * 100:+.2f} % | {r['ssim']:.3f} | "
                             f"{num(r['speckle'])} |")
    lines += ["", "**At equal time and equal error**, each variant against power sampling with "
              "the same integrator (IGI: power's 16 frames; the path tracer: power's 4 frames of "
              "16 spp): its relMSE at power's time, and the time it needs for power's relMSE "
              "(log-log interpolation between the measured points):", "",
              "| scene | variant | against | relMSE at that time | power's relMSE / this | "
              "time to power's relMSE | speed-up | speckle after 1 frame |",
              "|---|---|---|---:|---:|---:|---:|---:|"]
    for name, s in summary.items():
        for v in results[name]:
            if v not in s:
                continue
            r = s[v]
            reach = (num(r["seconds_to_anchor_error"]) + " s"
                     + (f" ({r['extrapolated']})" if r["extrapolated"] else ""))
            lines.append(f"| {name} | {v} | {r['anchor']} ({r['anchor_seconds']:.2f} s, "
                         f"{num(r['anchor_relmse'])}) | {num(r['relmse_at_anchor_time'])} | "
                         f"{num(r['error_ratio_power_over_this'])} | {reach} | "
                         f"{num(r['speedup_at_anchor_error'])} | {num(r['speckle_1'])} |")
    lines += ["", "![relMSE against time, per scene and variant](perf/many-lights.png)"]
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "many-lights"))
    ap.add_argument("--docs", default=os.path.join(ROOT, "docs"),
                    help="where PERFORMANCE.md and perf/ are; empty: write no docs")
    ap.add_argument("--scenes", default=",".join(SCENES))
    ap.add_argument("--variants", default=",".join(VARIANTS))
    ap.add_argument("--seeds", default="1,2")
    ap.add_argument("--ref-spp", type=int, default=2048)
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=240)
    ap.add_argument("--command", default="scripts/bench_many_lights.sh")
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--replot", default="",
                    help="write the documents again from this results.json, rendering nothing")
    args = ap.parse_args()
    args.scenes = [s for s in args.scenes.split(",") if s]
    args.variants = [v for v in args.variants.split(",") if v]
    for s in args.scenes:
        if s not in SCENES:
            sys.exit(f"unknown scene {s}: one of {', '.join(SCENES)}")
    for v in args.variants:
        if v not in VARIANTS:
            sys.exit(f"unknown variant {v}: one of {', '.join(VARIANTS)}")
    args.seeds = [int(s) for s in args.seeds.split(",") if s]
    if args.quick:
        args.seeds = args.seeds[:1]
        args.ref_spp = min(args.ref_spp, 256)
        for v in VARIANTS.values():
            v[2][:] = [f for f in v[2] if f <= 4]
        args.out = args.out.rstrip("/") + "-quick"
        args.docs = ""
    if args.replot:
        # The documents again from a run's results.json (its machine, time and build kept).
        with open(args.replot, encoding="utf-8") as f:
            saved = json.load(f)
        env, results, wall = saved["machine"], saved["results"], saved.get("wall_seconds", 0)
        args.command, args.build_identity = saved.get("command", args.command), saved.get("build")
    else:
        env = machine()
        t0 = time.time()
        results = measure(args)
        wall = time.time() - t0
        args.build_identity = build_identity()
    summary = summarize(results)
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "results.json"), "w", encoding="utf-8") as f:
        json.dump({"machine": env, "command": args.command, "build": args.build_identity,
                   "wall_seconds": wall, "results": results, "summary": summary}, f, indent=1)
    text = markdown(args, results, summary, env, wall)
    print(text)
    if args.docs:
        perf = os.path.join(args.docs, "perf")
        os.makedirs(perf, exist_ok=True)
        with open(os.path.join(perf, "many-lights.json"), "w", encoding="utf-8") as f:
            json.dump({"machine": env, "command": args.command, "build": args.build_identity,
                       "wall_seconds": wall, "results": results, "summary": summary}, f,
                      indent=1)
        plot(results, os.path.join(perf, "many-lights.png"))
        splice(os.path.join(args.docs, "PERFORMANCE.md"), {"many-lights": text}, log)


if __name__ == "__main__":
    main()
