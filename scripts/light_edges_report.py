#!/usr/bin/env python3
"""What the light-edge rays (render.light_edge_rays, docs/ACCURACY.md "Light edges") do.

Runs each scene of docs/ACCURACY.md twice with the same seed and the same build, once with
--light-edge-rays 0 (the eye ray's own hit alone) and once with the default, and sets side by
side, after 4, 16, 64 and --frames accumulated frames, the relMSE against the scene's cached
path-traced reference (minus its noise floor, as error_estimate_report.py does), and the rays and
the median seconds of a frame. The sessions alternate scene by scene, so that both settings meet
the same load on a shared machine. Writes docs/accuracy/light-edges.csv and the block
"light-edges" of docs/ACCURACY.md.

  scripts/light_edges_report.py [--build build] [--scenes a,b] [--frames 256] [--render-references]

Python 3 standard library only (plus igi-compare and, for new references, oiiotool).
"""

import argparse
import json
import os
import statistics
import sys

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import accuracy_report  # noqa: E402
import error_estimate_report  # noqa: E402
import report_util  # noqa: E402
from report_util import num, run  # noqa: E402

ROOT = accuracy_report.ROOT


def session(scene, args, folder, rays, ks):
    """One session; returns (per-frame stats by accumulated count, image path pattern)."""
    os.makedirs(folder, exist_ok=True)
    stats = os.path.join(folder, "stats.json")
    sequence = os.path.join(folder, "frame_%04d.exr")
    cmd = [os.path.join(args.build, "bin", "igi-master"), "--scene", scene[0], *scene[1],
           "--local-clients", str(args.clients), "--width", str(args.width), "--height", str(args.height),
           "--frames", str(args.frames), "--seed", str(args.seed), "--stats-json", stats,
           "--output-sequence", sequence, "--sequence-frames", ",".join(str(k - 1) for k in ks),
           "--log-level", "error", *(["--light-edge-rays", "0"] if rays == 0 else [])]
    run(cmd)
    with open(stats, encoding="utf-8") as f:
        frames = json.load(f)["frames"]
    return frames, sequence


def measure(bench, spec, args):
    scene = bench.scene_file(spec)
    ref, info = bench.reference(spec.name, scene, spec.ref_factor) if (
        args.render_references or error_estimate_report.bench_has_reference(bench, spec, scene)) else (None, None)
    ks = sorted({k for k in (4, 16, 64, args.frames) if k <= args.frames})
    out = {}
    for rays in (0, None):  # None: the default
        name = "off" if rays == 0 else "on"
        frames, sequence = session(scene, args, os.path.join(args.out, spec.name, name), rays, ks)
        errors = {}
        for k in ks:
            image = sequence.replace("%04d", f"{k - 1:04d}")
            if ref:
                errors[k] = bench.compare(image, ref)["relative_mse"] - info["noise_floor_relative_mse"]
            os.remove(image)
        out[name] = {"rays": statistics.mean(f["rays"] for f in frames),
                     "seconds": statistics.median(f["seconds"] for f in frames), "errors": errors}
    pixels = args.width * args.height
    rows = []
    for k in ks:
        off, on = out["off"]["errors"].get(k), out["on"]["errors"].get(k)
        rows.append({"scene": spec.name, "frames": k, "rel_mse_off": off, "rel_mse_on": on,
                     "error_ratio": off / on if off and on and on > 0 else None,
                     "rays_per_pixel_off": out["off"]["rays"] / pixels, "rays_per_pixel_on": out["on"]["rays"] / pixels,
                     "seconds_off": out["off"]["seconds"], "seconds_on": out["on"]["seconds"]})
        log(f"  {spec.name} {k:4d} frames: relMSE - floor {num(off)} off, {num(on)} on")
    log(f"  {spec.name}: rays per pixel {rows[0]['rays_per_pixel_off']:.2f} -> {rows[0]['rays_per_pixel_on']:.2f}, "
        f"median frame {rows[0]['seconds_off']:.3f} s -> {rows[0]['seconds_on']:.3f} s")
    return rows


def log(msg):
    accuracy_report.log(msg)


def table(rows, ks):
    head = ("| scene | rays per pixel (off / on) | median frame, s (off / on) | " +
            " | ".join(f"relMSE - floor after {k} (off / on, ratio)" for k in ks) + " |")
    lines = [head, "|" + "---|" * (3 + len(ks))]
    by_scene = {}
    for r in rows:
        by_scene.setdefault(r["scene"], []).append(r)
    for scene, rs in by_scene.items():
        cells = [scene, f"{rs[0]['rays_per_pixel_off']:.2f} / {rs[0]['rays_per_pixel_on']:.2f}",
                 f"{rs[0]['seconds_off']:.3f} / {rs[0]['seconds_on']:.3f}"]
        for k in ks:
            r = next((x for x in rs if x["frames"] == k), None)
            if r is None or r["rel_mse_off"] is None:
                cells.append("-")
            else:
                ratio = f"{r['error_ratio']:.2f}x" if r["error_ratio"] else "-"
                cells.append(f"{num(r['rel_mse_off'])} / {num(r['rel_mse_on'])}, {ratio}")
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    accuracy_report.add_bench_arguments(p, "light-edges", "ACCURACY.md", "light-edges.csv", ref_frames=64)
    p.add_argument("--render-references", action="store_true")
    p.add_argument("--command", default="scripts/light_edges_report.py")
    a = p.parse_args()
    names = [s for s in a.scenes.split(",") if s] or accuracy_report.SCENE_NAMES
    bench = accuracy_report.bench_for(a)
    started = report_util.machine()
    rows = []
    for name in names:
        spec = next(s for s in accuracy_report.SCENES if s.name == name)
        if not os.path.exists(spec.path):
            log(f"{spec.name}: {spec.path} missing, skipped")
            continue
        rows += measure(bench, spec, a)
    finished = report_util.machine()
    report_util.write_rows_csv(a.csv, rows)
    ks = sorted({r["frames"] for r in rows})
    head = [f"- command: `{a.command}`",
            f"- machine: {started['nproc']} cores ({started['cpu']}); started {started['date']} (load {started['load']}), "
            f"finished {finished['date']} (load {finished['load']})",
            f"- {a.width} x {a.height}, {a.clients} local clients, seed {a.seed}, default settings but "
            f"`--light-edge-rays 0` for \"off\"; the relMSE against the scene's path-traced reference "
            f"({a.ref_spp * a.ref_frames} spp) minus its noise floor; every point in {os.path.relpath(a.csv, ROOT)}", ""]
    report_util.splice(a.doc, {"light-edges": "\n".join(head) + "\n" + table(rows, ks)}, log)
    log(f"{a.doc} and {a.csv} written")


if __name__ == "__main__":
    main()
