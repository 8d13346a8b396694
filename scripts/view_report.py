#!/usr/bin/env python3
"""Writes the web view's block of docs/PERFORMANCE.md from docs/perf/view.json
(scripts/bench_view.sh): key-to-image latency and the frame rate with the view open or not."""
import argparse
import datetime
import json
import re
import statistics
import subprocess


def main():
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--json", required=True)
    p.add_argument("--doc", required=True)
    p.add_argument("--command", required=True)
    p.add_argument("--seconds", type=int, default=0)
    p.add_argument("--build", default="build")
    a = p.parse_args()
    with open(a.json, encoding="utf-8") as f:
        r = json.load(f)
    rev = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                         text=True).stdout.strip() or "?"
    lat = r["latency"]
    ms = [x["ms"] for x in lat]
    frames = [x["frames"] for x in lat]
    with_view, without = r["fps"]["with"], r["fps"]["without"]
    cost = 1 - statistics.mean(with_view) / statistics.mean(without)
    L = [
        f"Measured on {datetime.date.today()} by `{a.command}` ({a.seconds // 60} min "
        f"{a.seconds % 60} s), build `{rev}`, on this 2-core machine: the default scene at "
        "640 x 480, paper settings, master and two local clients, Debian's Chromium headless on "
        "the same two cores (so the browser's decoding and painting are part of the cost).",
        "",
        "**Key to image** (a key press in the page to the first image that shows the move, "
        f"{len(ms)} presses 1.5 s apart; a frame time is 1 / the fps the master reported then):",
        "",
        "| | median | min | max |",
        "|---|---|---|---|",
        f"| milliseconds | {statistics.median(ms):.0f} | {min(ms):.0f} | {max(ms):.0f} |",
        f"| frame times | {statistics.median(frames):.2f} | {min(frames):.2f} | "
        f"{max(frames):.2f} |",
        "",
        "**Frame rate with the view open against without** (40-frame runs, alternating):",
        "",
        "| | runs (fps) | mean |",
        "|---|---|---|",
        f"| without a view | {', '.join(f'{x:.3f}' for x in without)} | "
        f"{statistics.mean(without):.3f} |",
        f"| one page open | {', '.join(f'{x:.3f}' for x in with_view)} | "
        f"{statistics.mean(with_view):.3f} |",
        "",
        f"The view costs the render {100 * cost:.1f} % of its frame rate"
        + (" (a gain is noise)." if cost < 0 else "."),
    ]
    block = "\n".join(L)
    with open(a.doc, encoding="utf-8") as f:
        text = f.read()
    pattern = re.compile(r"(<!-- BEGIN GENERATED view -->\n).*?(\n?<!-- END GENERATED view -->)",
                         re.S)
    if not pattern.search(text):
        raise SystemExit(f"{a.doc} has no <!-- BEGIN GENERATED view --> block")
    text = pattern.sub(lambda m: m.group(1) + block + "\n" + m.group(2).lstrip("\n"), text)
    with open(a.doc, "w", encoding="utf-8") as f:
        f.write(text)
    print(block)


if __name__ == "__main__":
    main()
