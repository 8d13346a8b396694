#!/usr/bin/env python3
"""How far the master's error estimate can be trusted (docs/ERROR_ESTIMATE.md).

igi-master estimates the accumulated image's relMSE without a reference, from the spread of
its frames (two half-means of the even and odd frames; common/render/RowAccumulator.h derives
it) and writes it per frame to --stats-json ("estimated_rel_mse"). This script runs the scenes
of docs/ACCURACY.md, one session of --frames accumulated frames each, keeps the images after
4, 8, ..., --frames frames, compares each with the scene's path-traced reference (the cached
ones of accuracy_report.py, rendered there when missing) and sets the estimate beside the true
relMSE, raw and with the reference's noise floor subtracted (relMSE(image, reference) is about
relMSE(image, truth) + the floor). A second session with another seed gives, without any
reference, the part of the error the estimate is for: relMSE(session 1, session 2) / 2 is the
noise of one session (its bias excluded), on every scene. Scenes without a cached reference get
that column only, unless --render-references. It writes docs/accuracy/error-estimate.csv and the block
"error-estimate" of docs/ERROR_ESTIMATE.md.

  scripts/error_estimate_report.py [--build build] [--scenes a,b] [--width 160 --height 120]
                                   [--frames 256] [--ref-spp 64 --ref-frames 256]

Python 3 standard library only (plus igi-compare and, for new references, oiiotool).
"""

import argparse
import csv
import hashlib
import json
import os
import sys

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import accuracy_report  # noqa: E402
import report_util  # noqa: E402
from report_util import num, run  # noqa: E402

ROOT = accuracy_report.ROOT
RATIO_LIMIT = 1.5  # the factor the estimate is to be within, where bias is below the noise


def log(msg):
    accuracy_report.log(msg)


def checkpoints(frames):
    """Accumulated frame counts 4, 8, 16, ... up to `frames` (and `frames`)."""
    return accuracy_report.frame_counts(frames, start=4)


def session(bench, scene, args, folder, seed, ks):
    """One session of args.frames frames; returns (per-frame stats by accumulated count, image
    path pattern)."""
    os.makedirs(folder, exist_ok=True)
    stats = os.path.join(folder, "stats.json")
    sequence = os.path.join(folder, "frame_%04d.exr")
    cmd = [os.path.join(args.build, "bin", "igi-master"), "--scene", scene[0], *scene[1],
           "--local-clients", str(args.clients), "--width", str(args.width), "--height", str(args.height),
           "--frames", str(args.frames), "--seed", str(seed), "--stats-json", stats,
           "--output-sequence", sequence, "--sequence-frames", ",".join(str(k - 1) for k in ks),
           "--log-level", "error"]
    run(cmd)
    with open(stats, encoding="utf-8") as f:
        frames = {fr["accumulated"]: fr for fr in json.load(f)["frames"]}
    return frames, sequence


def ratio(a, b):
    return a / b if b is not None and b > 0 else float("inf")


def measure(bench, spec, args):
    scene = bench.scene_file(spec)
    ref, info = None, None
    if args.render_references or bench_has_reference(bench, spec, scene):
        ref, info = bench.reference(spec.name, scene, spec.ref_factor)
    ks = checkpoints(args.frames)
    log(f"{spec.name}: two sessions of {args.frames} frames (seeds {args.seed}, {args.seed + 1})")
    frames, sequence = session(bench, scene, args, os.path.join(args.out, spec.name, "a"), args.seed, ks)
    _, other = session(bench, scene, args, os.path.join(args.out, spec.name, "b"), args.seed + 1, ks)
    rows = []
    for k in ks:
        image = sequence.replace("%04d", f"{k - 1:04d}")
        second = other.replace("%04d", f"{k - 1:04d}")
        est = frames[k]["estimated_rel_mse"]
        # Two independent sessions: relMSE(a, b) is about twice the relMSE of one against its
        # expectation, the part the estimate estimates (the noise, bias excluded).
        noise = bench.compare(image, second)["relative_mse"] / 2
        row = {"scene": spec.name, "frames": k, "estimated": est, "noise": noise, "ratio_noise": ratio(est, noise),
               "true": None, "floor": None, "true_minus_floor": None, "ratio": None, "bias": None}
        if ref:
            err = bench.compare(image, ref)
            floor = info["noise_floor_relative_mse"]
            row.update(true=err["relative_mse"], floor=floor, true_minus_floor=err["relative_mse"] - floor,
                       bias=err["mean_relative_bias"])
            row["ratio"] = ratio(est, row["true_minus_floor"])
        rows.append(row)
        log(f"  {k:4d} frames: estimated {est:.4g}, between sessions / 2 {noise:.4g} "
            f"(ratio {row['ratio_noise']:.3f})" +
            (f", true {row['true']:.4g} - floor {row['floor']:.3g}: ratio {row['ratio']:.3f}, "
             f"bias {row['bias']:+.4f}" if ref else ""))
        os.remove(image)
        os.remove(second)
    return rows, info


def bench_has_reference(bench, spec, scene):
    """Whether the reference is cached (rendering one takes minutes to hours): the cache key of
    accuracy_report.Bench.reference, scene file digest included."""
    a = bench.args
    half_frames = a.ref_frames * spec.ref_factor // 2
    total = a.ref_spp * half_frames * 2
    with open(scene[0], "rb") as f:
        digest = hashlib.sha1(f.read()).hexdigest()[:8]
    tag = f"{spec.name}-{a.width}x{a.height}-{total}spp-{a.ref_spp}x{half_frames}x2-{digest}"
    return all(os.path.exists(os.path.join(a.ref, tag + ext)) for ext in (".exr", ".json"))


def within(x):
    return x is not None and 1 / RATIO_LIMIT <= x <= RATIO_LIMIT


def table(rows, info):
    lines = ["| frames | estimated relMSE | between two sessions / 2 | estimated / that | true relMSE | "
             "true - floor | estimated / (true - floor) | bias (image mean) | within 1.5x (noise; true) |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        true_part = ("| - | - | - | - " if r["true"] is None else
                     f"| {num(r['true'])} | {num(r['true_minus_floor'])} | {r['ratio']:.2f} | {r['bias']:+.4f} ")
        verdict = ("yes" if within(r["ratio_noise"]) else "**no**") + "; " + (
            "-" if r["true"] is None else "yes" if within(r["ratio"]) else "**no**")
        lines.append(f"| {r['frames']} | {num(r['estimated'])} | {num(r['noise'])} | {r['ratio_noise']:.2f} "
                     f"{true_part}| {verdict} |")
    return "\n".join(lines)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    p.add_argument("--out", default=os.path.join(ROOT, "out", "error-estimate"))
    p.add_argument("--ref", default=os.path.join(ROOT, "out", "reference"), help="cached references (not in git)")
    p.add_argument("--doc", default=os.path.join(ROOT, "docs", "ERROR_ESTIMATE.md"))
    p.add_argument("--csv", default=os.path.join(ROOT, "docs", "accuracy", "error-estimate.csv"))
    p.add_argument("--scenes", default="", help="comma-separated subset of: " + ", ".join(accuracy_report.SCENE_NAMES))
    p.add_argument("--width", type=int, default=160)
    p.add_argument("--height", type=int, default=120)
    p.add_argument("--clients", type=int, default=2)
    p.add_argument("--frames", type=int, default=256)
    p.add_argument("--seed", type=int, default=3, help="igi's session seed (the references use 1 and 2)")
    p.add_argument("--render-references", action="store_true",
                   help="render the references that are not cached (else scenes without one get the "
                        "between-sessions column only)")
    p.add_argument("--ref-spp", type=int, default=64)
    p.add_argument("--ref-frames", type=int, default=256, help="both halves together: 16384 spp by default")
    p.add_argument("--command", default="scripts/error_estimate_report.py")
    a = p.parse_args()
    a.build = os.path.abspath(a.build)
    names = [s for s in a.scenes.split(",") if s] or accuracy_report.SCENE_NAMES
    # accuracy_report's Bench renders and caches the references (same cache keys).
    bench_args = argparse.Namespace(build=a.build, baseline_bin="", out=a.out, ref=a.ref, clients=a.clients,
                                    width=a.width, height=a.height, ref_spp=a.ref_spp, ref_frames=a.ref_frames)
    bench = accuracy_report.Bench(bench_args)
    started = report_util.machine()
    all_rows, blocks = [], []
    for name in names:  # in the order asked for
        spec = next(s for s in accuracy_report.SCENES if s.name == name)
        if not os.path.exists(spec.path):
            log(f"{spec.name}: {spec.path} missing, skipped")
            continue
        rows, info = measure(bench, spec, a)
        all_rows += rows
        what = (f"reference {info['spp_total']} spp, noise floor relMSE {num(info['noise_floor_relative_mse'])}"
                if info else "no cached reference")
        blocks.append(f"#### {spec.name} ({a.width} x {a.height}; {what})\n\n{table(rows, info)}\n")
    finished = report_util.machine()
    os.makedirs(os.path.dirname(a.csv), exist_ok=True)
    with open(a.csv, "w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, fieldnames=list(all_rows[0].keys()))
        w.writeheader()
        w.writerows(all_rows)
    near_noise = [r for r in all_rows if within(r["ratio_noise"])]
    judged = [r for r in all_rows if r["true"] is not None]
    near_true = [r for r in judged if within(r["ratio"])]
    head = [f"- command: `{a.command}`",
            f"- machine: {started['nproc']} cores ({started['cpu']}); started {started['date']} (load {started['load']}), "
            f"finished {finished['date']} (load {finished['load']})",
            f"- {a.width} x {a.height}, {a.clients} local clients, seed {a.seed}, default settings; one session of "
            f"{a.frames} frames per scene and a second one (seed {a.seed + 1}) for the between-sessions "
            f"column; every point in {os.path.relpath(a.csv, ROOT)}",
            f"- within a factor of {RATIO_LIMIT} of the between-sessions noise: {len(near_noise)} of {len(all_rows)} "
            f"points; of (true - floor): {len(near_true)} of {len(judged)} points with a reference", ""]
    report_util.splice(a.doc, {"error-estimate": "\n".join(head) + "\n" + "\n".join(blocks)}, log)
    log(f"within {RATIO_LIMIT}x: {len(near_noise)} of {len(all_rows)} (noise), {len(near_true)} of {len(judged)} "
        f"(true - floor); {a.doc} and {a.csv} written")


if __name__ == "__main__":
    main()
