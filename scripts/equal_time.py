#!/usr/bin/python3
"""Two renderers' accumulation curves at equal time, from an accuracy run's results.csv.

For each scene and each point of the `--old` renderer's curve (time t, relMSE e_old), the `--new`
renderer's relMSE at the same time t, interpolated log-log between its two nearest points (no
extrapolation: outside the new curve's time range the point is skipped), and e_old / e_new: above
1 where the new renderer has less error at equal time. Prints a Markdown table per scene and the
smallest ratio; exits 1 if any ratio is below --at-least (default: report only).

Usage: scripts/equal_time.py docs/accuracy/many-lights/results.csv --new igi --old igi-baseline
"""

import argparse
import csv
import math
import sys


def curve(rows, scene, renderer):
    """(time, relMSE) of an accumulation curve, by time."""
    points = [(float(r["time"]), float(r["relmse"])) for r in rows
              if r["scene"] == scene and r["renderer"] == renderer and r["sweep"] == "frames"]
    return sorted(p for p in points if p[0] > 0 and p[1] > 0)


def at(points, t):
    """The curve's relMSE at time t, log-log between its neighbours; None outside its range."""
    for (t0, e0), (t1, e1) in zip(points, points[1:]):
        if t0 <= t <= t1:
            if t1 == t0:
                return e0
            s = (math.log(t) - math.log(t0)) / (math.log(t1) - math.log(t0))
            return math.exp(math.log(e0) + s * (math.log(e1) - math.log(e0)))
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("csv")
    ap.add_argument("--new", default="igi")
    ap.add_argument("--old", default="igi-baseline")
    ap.add_argument("--at-least", type=float, default=None)
    a = ap.parse_args()
    with open(a.csv, encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    worst = None
    for scene in dict.fromkeys(r["scene"] for r in rows):
        old, new = curve(rows, scene, a.old), curve(rows, scene, a.new)
        if not old or not new:
            continue
        print(f"\n{scene}: {a.new} against {a.old} at equal time\n")
        print(f"| time (s) | relMSE {a.old} | relMSE {a.new} | {a.old} / {a.new} |")
        print("|---:|---:|---:|---:|")
        for t, e in old:
            e_new = at(new, t)
            if e_new is None:
                continue
            ratio = e / e_new
            worst = ratio if worst is None else min(worst, ratio)
            print(f"| {t:.3g} | {e:.3g} | {e_new:.3g} | {ratio:.2f} |")
    if worst is None:
        sys.exit(f"no scene has both '{a.new}' and '{a.old}' curves in {a.csv}")
    print(f"\nsmallest {a.old} / {a.new} relMSE ratio at equal time: {worst:.2f}")
    if a.at_least is not None and worst < a.at_least:
        sys.exit(1)


if __name__ == "__main__":
    main()
