#!/usr/bin/env python3
"""The first frame after a change, this build against a baseline build (docs/PERFORMANCE.md,
"The first frame after a change"; issue 36 asks for it faster at equal or lower error).

Per scene, both builds render the same sessions (seeds --seeds, default settings, 160 x 120, one
local client) and each image after 1, 4 and 16 accumulated frames is compared with the scene's
path-traced reference: relMSE minus the reference's noise floor (as error_estimate_report.py
does) and speckle (the share of pixels more than 4x the reference, igi-compare's). The first
frame's cost is the client's CPU seconds for --bench-frames first frames in igi-bench (one thread,
--bench-width x --bench-height), the two builds taking turns --bench-runs times so that they
meet the same load. The figure of merit is relMSE x CPU seconds, this build's over the
baseline's (below 1: less error for the same time). Writes docs/perf/first-frame.csv and the block
"first-frame" of docs/PERFORMANCE.md.

  scripts/first_frame_report.py --baseline-bin DIR [--build build] [--scenes a,b] [--seeds 6,7]
                                [--render-references]

Scenes without a cached reference are skipped unless --render-references is given. Python 3
standard library only (plus igi-compare and, for new references, oiiotool).
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
import shadow_rays_report  # noqa: E402
from report_util import run  # noqa: E402

ROOT = accuracy_report.ROOT
FRAMES = (1, 4, 16)
SPECS = {s.name: s for s in (*accuracy_report.SCENES, *error_estimate_report.HELD_OUT)}
SCENE_NAMES = [*SPECS, *shadow_rays_report.EXTRA]
# The scenes the first frame's settings were chosen on (with seeds 3-5, then 6-13); the others are
# held out.
TUNED = ("default", "interior-diffuse", "interior-glossy", "spot", "cornell-glossy", "sculptures")
HELD_OUT = tuple(n for n in SCENE_NAMES if n not in TUNED)


def log(msg):
    accuracy_report.log(msg)


def spec_for(name):
    return SPECS.get(name) or shadow_rays_report.spec_for(name)


def session(bin_dir, scene, args, folder, seed):
    """One session of max(FRAMES) frames; the paths of its images after each of FRAMES."""
    os.makedirs(folder, exist_ok=True)
    sequence = os.path.join(folder, "frame_%04d.exr")
    run([os.path.join(bin_dir, "igi-master"), "--scene", scene[0], *scene[1], "--local-clients",
         str(args.clients), "--width", str(args.width), "--height", str(args.height), "--frames",
         str(max(FRAMES)), "--seed", str(seed), "--output-sequence", sequence, "--sequence-frames",
         ",".join(str(k - 1) for k in FRAMES), "--log-level", "error"])
    return {k: sequence.replace("%04d", f"{k - 1:04d}") for k in FRAMES}


# glibc's trim and mmap thresholds raised, as scripts/bench_side_by_side.sh does: igi-bench from
# before 65a8fd3 handed every tile of a frame to its pool at once, and glibc then returned the
# freed tile buffers to the system and faulted them in again each frame, a cost of that bench and
# not of a session's client. With the thresholds raised either build measures its rendering.
BENCH_ENV = {**os.environ,
             "GLIBC_TUNABLES": "glibc.malloc.trim_threshold=1000000000:glibc.malloc.mmap_threshold=1000000000"}


def cpu_seconds(bin_dir, scene, args):
    """The client's CPU seconds for igi-bench's first frames (each rendered as the first after a
    change)."""
    proc, _ = run([os.path.join(bin_dir, "igi-bench"), "--scene", scene[0], *scene[1], "--threads", "1",
                   "--frames", str(args.bench_frames), "--segments", "100000", "--width", str(args.bench_width),
                   "--height", str(args.bench_height)], env=BENCH_ENV)
    # Builds from before b193d16 logged the scene's warnings to stdout, before the JSON.
    out = proc.stdout
    start = 0 if out.startswith("{") else out.find("\n{") + 1
    return json.loads(out[start:])["client_cpu_seconds"]


def measure(bench, spec, args, builds, seeds):
    scene = shadow_rays_report.scene_args(bench, spec)
    if not args.render_references and not error_estimate_report.bench_has_reference(bench, spec, scene):
        log(f"{spec.name}: no cached reference (--render-references renders it), skipped")
        return []
    ref, info = bench.reference(spec.name, scene, spec.ref_factor)
    floor = info["noise_floor_relative_mse"]
    seconds = {b: [] for b in builds}
    for _ in range(args.bench_runs):
        for b, bin_dir in builds.items():
            seconds[b].append(cpu_seconds(bin_dir, scene, args))
    # The ratio within each turn, whose two runs met the same load, then its median: the
    # machine's other users move both runs of a turn more than they move the ratio.
    ratio = statistics.median(t / t0 for t, t0 in zip(seconds["this"], seconds["baseline"]))
    rows = []
    for seed in seeds:
        for b, bin_dir in builds.items():
            images = session(bin_dir, scene, args, os.path.join(args.out, spec.name, f"{b}-seed{seed}"), seed)
            for k, image in images.items():
                c = bench.compare(image, ref)
                os.remove(image)
                rows.append({"scene": spec.name, "build": b, "seed": seed, "frames": k,
                             "rel_mse": c["relative_mse"] - floor, "speckle": c["speckle"],
                             "mean_relative_bias": c["mean_relative_bias"],
                             "cpu_seconds": statistics.median(seconds[b]),
                             "cpu_ratio": ratio})
    log(f"  {spec.name}: first frame relMSE - floor, medians over seeds: " + ", ".join(
        f"{b} {statistics.median(r['rel_mse'] for r in rows if r['build'] == b and r['frames'] == 1):.3g} "
        f"({statistics.median(seconds[b]):.3f} CPU s)" for b in builds))
    return rows


def median_of(rows, key):
    return statistics.median(r[key] for r in rows) if rows else None


def table(rows):
    head = ("| scene | CPU s, baseline | CPU s, this build | " +
            " | ".join(f"after {k}: relMSE, baseline / this build (ratio)" for k in FRAMES) +
            " | first frame: speckle, baseline / this build | first frame: error x time |")
    lines = [head, "|" + "---|" * (5 + len(FRAMES))]
    for scene in dict.fromkeys(r["scene"] for r in rows):
        at = {(b, k): [r for r in rows if r["scene"] == scene and r["build"] == b and r["frames"] == k]
              for b in ("baseline", "this") for k in FRAMES}
        t0, t1 = median_of(at["baseline", 1], "cpu_seconds"), median_of(at["this", 1], "cpu_seconds")
        ratio = at["this", 1][0]["cpu_ratio"]
        label = scene + (" (held out)" if scene in HELD_OUT else "")
        cells = [label, f"{t0:.3f}", f"{t1:.3f} ({ratio:.2f}x)"]
        for k in FRAMES:
            e0, e1 = median_of(at["baseline", k], "rel_mse"), median_of(at["this", k], "rel_mse")
            cells.append(f"{e0:.3g} / {e1:.3g} ({e1 / e0:.2f})" if e0 and e0 > 0 else "-")
        s0, s1 = median_of(at["baseline", 1], "speckle"), median_of(at["this", 1], "speckle")
        cells.append(f"{s0:.2g} / {s1:.2g}")
        e0, e1 = median_of(at["baseline", 1], "rel_mse"), median_of(at["this", 1], "rel_mse")
        cells.append(f"{e1 / e0 * ratio:.2f}" if e0 and e0 > 0 else "-")
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    accuracy_report.add_bench_arguments(p, "first-frame", "PERFORMANCE.md", "first-frame.csv", ref_frames=64,
                                        scenes=",".join(SCENE_NAMES))
    p.set_defaults(csv=os.path.join(ROOT, "docs", "perf", "first-frame.csv"), clients=1)
    p.add_argument("--baseline-bin", required=True, help="the baseline build's bin/ folder")
    p.add_argument("--seeds", default="6,7,8,9,10,11,12,13")
    p.add_argument("--bench-runs", type=int, default=5)
    p.add_argument("--bench-frames", type=int, default=3)
    p.add_argument("--bench-width", type=int, default=320)
    p.add_argument("--bench-height", type=int, default=240)
    p.add_argument("--render-references", action="store_true")
    p.add_argument("--command", default="scripts/first_frame_report.py")
    a = p.parse_args()
    seeds = [int(s) for s in a.seeds.split(",")]
    names = report_util.scene_names(a.scenes, SCENE_NAMES)
    bench = accuracy_report.bench_for(a)
    builds = {"baseline": os.path.abspath(a.baseline_bin), "this": os.path.join(a.build, "bin")}
    base_rev = run([os.path.join(builds["baseline"], "igi-master"), "--version"])[0].stdout
    this_rev = run([os.path.join(builds["this"], "igi-master"), "--version"])[0].stdout
    started = report_util.machine()
    rows = report_util.measure_scenes(names, spec_for, lambda spec: measure(bench, spec, a, builds, seeds), log)
    finished = report_util.machine()
    report_util.write_rows_csv(a.csv, rows)
    head = [f"- command: `{a.command}`",
            f"- builds: baseline `{base_rev.strip()}`, this build `{this_rev.strip()}`",
            f"- machine: {started['nproc']} cores ({started['cpu']}); started {started['date']} (load {started['load']}), "
            f"finished {finished['date']} (load {finished['load']})",
            f"- images {a.width} x {a.height}, {a.clients} local client(s), default settings, seeds {a.seeds} "
            f"(medians); relMSE against the scene's path-traced reference ({a.ref_spp * a.ref_frames} spp) minus "
            f"its noise floor; CPU s: the client's CPU seconds for {a.bench_frames} first frames at "
            f"{a.bench_width} x {a.bench_height} on one thread (igi-bench with glibc's trim and mmap thresholds raised, "
            f"{a.bench_runs} runs of each build taken in turns: the medians, and in brackets the median of the ratios "
            f"within a turn); \"error x time\": "
            f"first-frame relMSE x CPU s, this build's over the baseline's, with that ratio (below 1: less error for "
            f"the same time); every point in {os.path.relpath(a.csv, ROOT)}", ""]
    report_util.splice(a.doc, {"first-frame": "\n".join(head) + "\n" + table(rows)}, log)
    log(f"{a.doc} and {a.csv} written")


if __name__ == "__main__":
    main()
