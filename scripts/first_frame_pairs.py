#!/usr/bin/env python3
"""The first frame after a change with other light samples and VPLs per point: its error and time.

How RenderSettings' kAutoFirstFrameDivisor was chosen. Per scene and pair "D+V" (D light
samples, V VPLs per point; "D+V/P" with a pool of P VPLs per set), the first frame of a session
with `--direct-samples D --indirect-vpls V [--vpl-pool P] --first-frame-divisor 1`:
  - its relMSE against the scene's cached path-traced reference (as scripts/first_frame_report.py
    makes them, out/reference) minus the reference's noise floor, the median over --seeds, at
    160 x 120 with one local client;
  - the client's render seconds (the stats' busy time of its threads) for 3 frames without
    accumulation at 320 x 240, the pairs taking turns --rounds times; the ratio to the first
    pair's within each round.

Usage:
  scripts/first_frame_pairs.py --scene NAME=FILE=REFERENCE [--scene ...] [--build build]
                               [--seeds 6,...,13] [--rounds 2] PAIR [PAIR ...]
e.g.
  scripts/first_frame_pairs.py \\
    --scene interior-diffuse=scenes/interior/diffuse.json=out/reference/interior-diffuse-160x120-4096spp-64x32x2-0c8017e7.exr \\
    4+18 2+6 2+6/48 1+5
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile


def parse_pair(text):
    direct, rest = text.split("+")
    vpls, _, pool = rest.partition("/")
    args = ["--direct-samples", direct, "--indirect-vpls", vpls, "--first-frame-divisor", "1"]
    if pool:
        args += ["--vpl-pool", pool]
    return args


def first_frame_error(bin_dir, scene, reference, seed, pair_args, scratch):
    floor = json.load(open(os.path.splitext(reference)[0] + ".json"))["noise_floor_relative_mse"]
    image = os.path.join(scratch, f"first-{seed}.exr")
    subprocess.run([os.path.join(bin_dir, "igi-master"), "--scene", scene, "--allow-outside-paths",
                    "--local-clients", "1", "--width", "160", "--height", "120", "--frames", "1",
                    "--seed", str(seed), "--output", image, "--log-level", "error", *pair_args],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    out = subprocess.run([os.path.join(bin_dir, "igi-compare"), image, reference], check=True,
                         capture_output=True, text=True).stdout
    return json.loads(out)["relative_mse"] - floor


def render_seconds(bin_dir, scene, pair_args, scratch):
    stats = os.path.join(scratch, "stats.json")
    subprocess.run([os.path.join(bin_dir, "igi-master"), "--scene", scene, "--allow-outside-paths",
                    "--local-clients", "1", "--width", "320", "--height", "240", "--frames", "3",
                    "--no-accumulate", "--stats-json", stats, "--log-level", "error", *pair_args],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return sum(c["render_seconds"] for c in json.load(open(stats))["clients"])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scene", action="append", required=True, help="NAME=FILE=REFERENCE")
    ap.add_argument("--build", default="build")
    ap.add_argument("--seeds", default="6,7,8,9,10,11,12,13")
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("pairs", nargs="+")
    a = ap.parse_args()
    bin_dir = os.path.join(a.build, "bin")
    seeds = [int(s) for s in a.seeds.split(",")]
    print("| scene | pair | first-frame relMSE (median) | x first pair | render s, 3 frames "
          "(median) | x first pair (per round) |")
    print("|---|---|---:|---:|---:|---|")
    with tempfile.TemporaryDirectory() as scratch:
        for spec in a.scene:
            name, scene, reference = spec.split("=")
            errors = {p: statistics.median(first_frame_error(bin_dir, scene, reference, s,
                                                             parse_pair(p), scratch)
                                           for s in seeds) for p in a.pairs}
            times = {p: [] for p in a.pairs}
            for _ in range(a.rounds):
                for p in a.pairs:
                    times[p].append(render_seconds(bin_dir, scene, parse_pair(p), scratch))
            first = a.pairs[0]
            for p in a.pairs:
                ratios = [t / f for t, f in zip(times[p], times[first])]
                print(f"| {name} | {p} | {errors[p]:.4g} | {errors[p] / errors[first]:.2f} | "
                      f"{statistics.median(times[p]):.3f} | "
                      f"{', '.join(f'{r:.2f}' for r in ratios)} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
