#!/usr/bin/env python3
"""What adaptive tiles gain (docs/ERROR_ESTIMATE.md, "Adaptive tiles").

With --target-error, igi-master leaves out the tile regions whose estimated error is at or below
the target (master/AdaptiveTiles.h). This script measures, per scene, the time and the work
(tiles rendered) to a true relMSE against the scene's path-traced reference, with adaptive
tiles and without (--no-adaptive-tiles), on scenes whose difficulty is uneven: the default
scene (a caustic through a glass ball), the glossy Cornell box and an interior.

Per scene: one session without a target for --frames frames gives the curve of the true relMSE
against frames (images after 8, 16, ... frames against the reference) and the targets (its
estimated relMSE after each of --target-frames frames). Then, per target, a session with it and
one with it and --no-adaptive-tiles, side by side: both stop at the first frame whose estimate is
at or below the target. Their true relMSE, frames, tiles and seconds are set beside each other,
and the plain curve says how many tiles and seconds the plain sessions needed to reach the
adaptive session's true relMSE (log-log interpolation between its checkpoints): the gain.

  scripts/adaptive_tiles_report.py [--build build] [--scenes a,b] [--width 160 --height 120]
                                   [--tile-size 8] [--frames 256] [--target-frames 32,64,128]

Writes docs/accuracy/adaptive-tiles.csv and the block "adaptive-tiles" of docs/ERROR_ESTIMATE.md.
Python 3 standard library only (plus igi-compare and, for new references, oiiotool).
"""

import argparse
import json
import math
import os
import sys

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import accuracy_report  # noqa: E402
import report_util  # noqa: E402
from report_util import num, run  # noqa: E402

ROOT = accuracy_report.ROOT
DEFAULT_SCENES = "default,cornell-glossy,interior-diffuse"


def log(msg):
    accuracy_report.log(msg)


def session(a, scene, folder, name, frames, extra, sequence_frames=None):
    """One igi-master session; returns its statistics and image (and sequence pattern)."""
    os.makedirs(folder, exist_ok=True)
    stats = os.path.join(folder, name + ".json")
    image = os.path.join(folder, name + ".exr")
    cmd = [os.path.join(a.build, "bin", "igi-master"), "--scene", scene[0], *scene[1],
           "--local-clients", str(a.clients), "--width", str(a.width), "--height", str(a.height),
           "--tile-size", str(a.tile_size), "--seed", str(a.seed), "--frames", str(frames),
           "--output", image, "--stats-json", stats, "--log-level", "error", *extra]
    sequence = None
    if sequence_frames:
        sequence = os.path.join(folder, name + "_%04d.exr")
        cmd += ["--output-sequence", sequence, "--sequence-frames", ",".join(str(k - 1) for k in sequence_frames)]
    _, wall = run(cmd)
    with open(stats, encoding="utf-8") as f:
        s = json.load(f)
    fr = s["frames"]
    return {"frames": len(fr), "seconds": s["seconds"], "wall": wall,
            "tiles": sum(f["tiles"] for f in fr), "left_out": sum(f.get("tiles_left_out", 0) for f in fr),
            "estimates": [f["estimated_rel_mse"] for f in fr], "image": image, "sequence": sequence}


def interpolate(curve, error):
    """Frames the plain curve [(frames, true relMSE)] needs to reach `error`: log-log between
    the checkpoints around it (extrapolated from the last two beyond them)."""
    pts = sorted((k, e) for k, e in curve if e > 0)
    if len(pts) < 2:
        return float("nan")
    for (k0, e0), (k1, e1) in zip(pts, pts[1:]):
        if e1 <= error <= e0 or (k1, e1) == pts[-1]:
            if e0 <= 0 or e1 <= 0 or e0 == e1:
                return float(k1)
            t = (math.log(error) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(k0) + t * (math.log(k1) - math.log(k0)))
    return float(pts[0][0])


def measure(bench, spec, a):
    scene = bench.scene_file(spec)
    ref, info = bench.reference(spec.name, scene, spec.ref_factor)
    floor = info["noise_floor_relative_mse"]
    folder = os.path.join(a.out, spec.name)
    ks = accuracy_report.frame_counts(a.frames, start=8)
    log(f"{spec.name}: {a.frames} frames without a target")
    free = session(a, scene, folder, "free", a.frames, [], ks)
    # relMSE against the reference is about the true one plus the reference's noise floor: the
    # floor is subtracted everywhere, or it would flatten the plain curve and inflate the gain.
    curve = []
    for k in ks:
        image = free["sequence"].replace("%04d", f"{k - 1:04d}")
        curve.append((k, bench.compare(image, ref)["relative_mse"] - floor))
        os.remove(image)
    tiles_per_frame = free["tiles"] / free["frames"]
    seconds_per_frame = free["seconds"] / free["frames"]
    log("  true relMSE - floor: " + ", ".join(f"{k}: {e:.4g}" for k, e in curve))
    rows = []
    for k in a.target_frames:
        target = free["estimates"][k - 1]
        log(f"  target {target:.4g} (the estimate after {k} frames)")
        extra = ["--target-error", repr(target)]
        cap = a.frames * 4
        plain = session(a, scene, folder, f"plain-{k}", cap, extra + ["--no-adaptive-tiles"])
        adaptive = session(a, scene, folder, f"adaptive-{k}", cap, extra)
        true_plain = bench.compare(plain["image"], ref)["relative_mse"] - floor
        true_adaptive = bench.compare(adaptive["image"], ref)["relative_mse"] - floor
        frames_needed = interpolate(curve, true_adaptive) if true_adaptive > 0 else float("nan")
        row = {"scene": spec.name, "target_frames": k, "target": target, "floor": floor,
               "plain_frames": plain["frames"], "plain_tiles": plain["tiles"], "plain_seconds": plain["seconds"],
               "plain_true": true_plain,
               "adaptive_frames": adaptive["frames"], "adaptive_tiles": adaptive["tiles"],
               "adaptive_left_out": adaptive["left_out"], "adaptive_seconds": adaptive["seconds"],
               "adaptive_true": true_adaptive,
               "plain_frames_to_adaptive_true": frames_needed,
               "tiles_gain": frames_needed * tiles_per_frame / max(1, adaptive["tiles"]),
               "seconds_gain": frames_needed * seconds_per_frame / adaptive["seconds"] if adaptive["seconds"] > 0 else None}
        rows.append(row)
        log(f"    plain {plain['frames']} frames {plain['seconds']:.2f} s true {true_plain:.4g}; adaptive "
            f"{adaptive['frames']} frames, {adaptive['tiles']} tiles ({adaptive['left_out']} left out), "
            f"{adaptive['seconds']:.2f} s, true {true_adaptive:.4g}; plain needs {frames_needed:.1f} frames for it: "
            f"gain {row['tiles_gain']:.2f}x tiles, {row['seconds_gain']:.2f}x seconds")
        for s in (plain, adaptive):
            os.remove(s["image"])
    return rows, info, curve


def table(rows):
    head = ("| target (plain estimate after) | plain: frames, s, true relMSE - floor | adaptive: frames, tiles "
            "rendered (left out), s, true relMSE - floor | plain frames to adaptive's true relMSE | gain in tiles | "
            "gain in seconds |\n"
            "|---|---|---|---|---|---|")
    lines = [head]
    for r in rows:
        lines.append(
            f"| {num(r['target'])} ({r['target_frames']} frames) | {r['plain_frames']}, {r['plain_seconds']:.2f} s, "
            f"{num(r['plain_true'])} | {r['adaptive_frames']}, {r['adaptive_tiles']} ({r['adaptive_left_out']}), "
            f"{r['adaptive_seconds']:.2f} s, {num(r['adaptive_true'])} | {r['plain_frames_to_adaptive_true']:.1f} | "
            f"**{r['tiles_gain']:.2f}x** | {num(r['seconds_gain'])}x |")
    return "\n".join(lines)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    accuracy_report.add_bench_arguments(p, "adaptive-tiles", "ERROR_ESTIMATE.md", "adaptive-tiles.csv",
                                        ref_frames=64, scenes=DEFAULT_SCENES)
    p.add_argument("--tile-size", type=int, default=8,
                   help="tile edge (default 8: at 160 x 120, 35 regions, as tiles of 32 give at 640 x 480)")
    p.add_argument("--target-frames", default="32,64,128",
                   help="the targets: the plain session's estimate after these frames")
    p.add_argument("--command", default="scripts/adaptive_tiles_report.py")
    a = p.parse_args()
    a.command = a.command.strip()
    a.target_frames = [int(k) for k in a.target_frames.split(",") if k]
    if any(k < 1 or k > a.frames for k in a.target_frames):
        sys.exit(f"--target-frames must lie in [1, --frames = {a.frames}]")
    bench = accuracy_report.bench_for(a)
    started = report_util.machine()
    all_rows, blocks = [], []
    for name in [s for s in a.scenes.split(",") if s]:
        spec = next(s for s in accuracy_report.SCENES if s.name == name)
        if not os.path.exists(spec.path):
            log(f"{spec.name}: {spec.path} missing, skipped")
            continue
        rows, info, curve = measure(bench, spec, a)
        all_rows += rows
        plain_curve = ", ".join(f"{k}: {num(e)}" for k, e in curve)
        blocks.append(f"#### {spec.name} ({a.width} x {a.height}, tiles of {a.tile_size}; reference "
                      f"{info['spp_total']} spp, noise floor relMSE {num(info['noise_floor_relative_mse'])})\n\n"
                      f"Plain session, true relMSE - floor after n frames: {plain_curve}.\n\n{table(rows)}\n")
    finished = report_util.machine()
    report_util.write_rows_csv(a.csv, all_rows)
    head = [f"- command: `{a.command}`",
            f"- machine: {started['nproc']} cores ({started['cpu']}); started {started['date']} (load {started['load']}), "
            f"finished {finished['date']} (load {finished['load']})",
            f"- {a.width} x {a.height}, {a.clients} local clients, seed {a.seed}, default settings but tiles of "
            f"{a.tile_size}; every row in {os.path.relpath(a.csv, ROOT)}",
            "- gain: the plain session's tiles (or seconds) to reach the adaptive session's true relMSE, over the "
            "adaptive session's own; seconds are wall time on a shared machine, tiles are the work", ""]
    report_util.splice(a.doc, {"adaptive-tiles": "\n".join(head) + "\n" + "\n".join(blocks)}, log)
    log(f"{a.doc} and {a.csv} written")


if __name__ == "__main__":
    main()
