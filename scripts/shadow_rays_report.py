#!/usr/bin/env python3
"""How many shadow rays per pixel IGI should trace where it chooses them by importance
(docs/PERFORMANCE.md, "Shadow rays per pixel"; render.direct_samples and indirect_vpls "auto").

Renders each scene with several (direct samples, indirect VPLs) pairs, the same seeds and the
same build, and sets side by side, after 1, 4, 16 and --frames accumulated frames, the relMSE
against the scene's path-traced reference (minus its noise floor, as error_estimate_report.py
does), the shadow rays per pixel and the median seconds of a frame. The figure of merit is
relMSE x seconds per frame (lower is better: the error that the same time buys), relative to the
paper's 4 + 18 within the same seed, and the same with shadow rays for seconds (a measure the
machine's load does not move). The pairs take turns seed by seed, so that they meet the same
load. Writes docs/perf/shadow-rays.csv and the block "shadow-rays" of docs/PERFORMANCE.md.

  scripts/shadow_rays_report.py [--build build] [--scenes a,b] [--pairs 4/18,2/9] [--seeds 3,4]
                                [--render-references]

The interiors were the scenes the choice was made on; the sculptures and the Sponza arcades
were measured after it, as held-out scenes. Python 3 standard library only (plus igi-compare and,
for new references, oiiotool).
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
from report_util import run  # noqa: E402

ROOT = accuracy_report.ROOT
BASE_PAIR = (4, 18)
# The many-light scenes: the two interiors of docs/ACCURACY.md (96 small lights), where the
# pair was chosen, and two held out (scenes/interior/sculptures.json: the interior with 133,000
# triangles of ceramics; scenes/sponza/arcades.json: 120 lights under Sponza's arcades).
EXTRA = {
    "sculptures": os.path.join(ROOT, "scenes/interior/sculptures.json"),
    "sponza-arcades": os.path.join(ROOT, "scenes/sponza/arcades.json"),
}
HELD_OUT = ("sculptures", "sponza-arcades")
SCENE_NAMES = ["interior-diffuse", "interior-glossy", *EXTRA]


def log(msg):
    accuracy_report.log(msg)


def spec_for(name):
    known = next((s for s in accuracy_report.SCENES if s.name == name), None)
    if known:
        return known
    return accuracy_report.SceneSpec(name, EXTRA[name], False, False, False, False, False)


def scene_args(bench, spec):
    path, extra = bench.scene_file(spec)
    # The arcades' meshes come from ../shared/scenes, outside the scene's folder.
    if spec.name == "sponza-arcades":
        extra = [*extra, "--allow-outside-paths"]
    return path, extra


def session(bench, scene, args, folder, pair, seed, ks):
    """One session of --frames frames; returns (per-frame stats, image path pattern)."""
    os.makedirs(folder, exist_ok=True)
    stats = os.path.join(folder, "stats.json")
    sequence = os.path.join(folder, "frame_%04d.exr")
    cmd = [os.path.join(args.build, "bin", "igi-master"), "--scene", scene[0], *scene[1],
           "--local-clients", str(args.clients), "--width", str(args.width), "--height", str(args.height),
           "--frames", str(args.frames), "--seed", str(seed), "--stats-json", stats,
           "--output-sequence", sequence, "--sequence-frames", ",".join(str(k - 1) for k in ks),
           "--direct-samples", str(pair[0]), "--indirect-vpls", str(pair[1]), "--log-level", "error"]
    run(cmd)
    with open(stats, encoding="utf-8") as f:
        return json.load(f)["frames"], sequence


def measure(bench, spec, args, pairs, seeds):
    scene = scene_args(bench, spec)
    if not args.render_references and not error_estimate_report.bench_has_reference(bench, spec, scene):
        log(f"{spec.name}: no cached reference (--render-references renders it), skipped")
        return []
    ref, info = bench.reference(spec.name, scene, spec.ref_factor)
    ks = sorted({k for k in (1, 4, 16, args.frames) if k <= args.frames})
    rows = []
    for seed in seeds:
        for pair in pairs:
            folder = os.path.join(args.out, spec.name, f"{pair[0]}-{pair[1]}-seed{seed}")
            frames, sequence = session(bench, scene, args, folder, pair, seed, ks)
            seconds = statistics.median(f["seconds"] for f in frames)
            rays = statistics.mean(f["shadow_rays_per_pixel"] for f in frames)
            for k in ks:
                image = sequence.replace("%04d", f"{k - 1:04d}")
                error = bench.compare(image, ref)["relative_mse"] - info["noise_floor_relative_mse"]
                os.remove(image)
                rows.append({"scene": spec.name, "held_out": spec.name in HELD_OUT, "seed": seed,
                             "direct_samples": pair[0], "indirect_vpls": pair[1], "frames": k,
                             "rel_mse": error, "seconds_per_frame": seconds, "shadow_rays_per_pixel": rays})
            log(f"  {spec.name} {pair[0]} + {pair[1]} seed {seed}: {rays:.1f} shadow rays per pixel, "
                f"median frame {seconds:.3f} s, relMSE - floor after {args.frames}: {rows[-1]['rel_mse']:.3g}")
    # Error x cost relative to the paper's pair, within each seed and frame count.
    for r in rows:
        base = next(b for b in rows if b["scene"] == r["scene"] and b["seed"] == r["seed"] and
                    b["frames"] == r["frames"] and (b["direct_samples"], b["indirect_vpls"]) == BASE_PAIR)
        good = r["rel_mse"] > 0 and base["rel_mse"] > 0
        r["error_x_time"] = (r["rel_mse"] * r["seconds_per_frame"]) / (base["rel_mse"] * base["seconds_per_frame"]) \
            if good else None
        r["error_x_rays"] = (r["rel_mse"] * r["shadow_rays_per_pixel"]) / (
            base["rel_mse"] * base["shadow_rays_per_pixel"]) if good else None
        r["error_ratio"] = r["rel_mse"] / base["rel_mse"] if good else None
    return rows


def median_of(rows, key):
    values = [r[key] for r in rows if r[key] is not None]
    return statistics.median(values) if values else None


def table(rows, pairs, ks):
    head = ("| scene | pair (direct + VPLs) | shadow rays per pixel | median frame, s | " +
            " | ".join(f"after {k}: relMSE, x 4+18; error x time (x rays)" for k in ks) + " |")
    lines = [head, "|" + "---|" * (4 + len(ks))]
    for scene in dict.fromkeys(r["scene"] for r in rows):
        for pair in pairs:
            rs = [r for r in rows if r["scene"] == scene and (r["direct_samples"], r["indirect_vpls"]) == pair]
            if not rs:
                continue
            label = scene + (" (held out)" if scene in HELD_OUT else "")
            cells = [label, f"{pair[0]} + {pair[1]}", f"{median_of(rs, 'shadow_rays_per_pixel'):.1f}",
                     f"{median_of(rs, 'seconds_per_frame'):.3f}"]
            for k in ks:
                at = [r for r in rs if r["frames"] == k]
                e, ratio = median_of(at, "rel_mse"), median_of(at, "error_ratio")
                t, x = median_of(at, "error_x_time"), median_of(at, "error_x_rays")
                cells.append(f"{e:.3g}, {ratio:.2f}; {t:.2f} ({x:.2f})" if None not in (e, ratio, t, x) else "-")
            lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    accuracy_report.add_bench_arguments(p, "shadow-rays", "PERFORMANCE.md", "shadow-rays.csv", ref_frames=64,
                                        scenes=",".join(SCENE_NAMES))
    p.set_defaults(csv=os.path.join(ROOT, "docs", "perf", "shadow-rays.csv"), clients=1, frames=64)
    p.add_argument("--pairs", default="4/18,2/9,4/9,2/18",
                   help="direct samples / indirect VPLs, comma-separated; 4/18 is the base")
    p.add_argument("--seeds", default="3,4")
    p.add_argument("--render-references", action="store_true")
    p.add_argument("--command", default="scripts/shadow_rays_report.py")
    a = p.parse_args()
    pairs = [tuple(int(x) for x in s.split("/")) for s in a.pairs.split(",")]
    if BASE_PAIR not in pairs:
        pairs.insert(0, BASE_PAIR)
    seeds = [int(s) for s in a.seeds.split(",")]
    names = report_util.scene_names(a.scenes, SCENE_NAMES)
    bench = accuracy_report.bench_for(a)
    started = report_util.machine()
    rows = report_util.measure_scenes(names, spec_for, lambda spec: measure(bench, spec, a, pairs, seeds), log)
    finished = report_util.machine()
    report_util.write_rows_csv(a.csv, rows)
    ks = sorted({r["frames"] for r in rows})
    head = [f"- command: `{a.command}`",
            f"- machine: {started['nproc']} cores ({started['cpu']}); started {started['date']} (load {started['load']}), "
            f"finished {finished['date']} (load {finished['load']})",
            f"- {a.width} x {a.height}, {a.clients} local client(s), seeds {a.seeds} (medians), default settings but "
            f"`--direct-samples` and `--indirect-vpls`; relMSE against the scene's path-traced reference "
            f"({a.ref_spp * a.ref_frames} spp) minus its noise floor; \"x 4+18\" is the relMSE over 4 + 18's at "
            f"the same frames, \"error x time\" relMSE x seconds per frame over 4 + 18's (below 1: less error "
            f"for the same time), in brackets with shadow rays per pixel for seconds; every point in "
            f"{os.path.relpath(a.csv, ROOT)}", ""]
    report_util.splice(a.doc, {"shadow-rays": "\n".join(head) + "\n" + table(rows, pairs, ks)}, log)
    log(f"{a.doc} and {a.csv} written")


if __name__ == "__main__":
    main()
