#!/usr/bin/env python3
"""The checks, table and plot of a soak run (scripts/soak.sh): reads its samples.csv (seconds,
name, pid, rss_kb, fds, threads, frames_done; one row per live process per sample) and writes
OUT/summary.md (a markdown table per process: lifetime, memory at the end of the warm-up and at
the end, the least-squares memory slope after the warm-up, descriptors and threads) and
OUT/soak.png (memory, descriptors and frame rate against time). Exits 1 if a check fails:
  - memory slope after the warm-up above --max-slope MB/hour, for the master and every client
    that lived through at least half of the time after the warm-up;
  - descriptors or threads of the master or a steady client growing: their maximum over the
    last third of the samples after the warm-up above the maximum over the first two thirds;
  - the master's exit code not 0, clients still running after it ended, or its --stats-json
    not valid JSON.
With --heap-log NAME=FILE (a client's log at debug) and --t0 (the samples' time 0, seconds since
the epoch), it also tabulates and plots that client's heap in use and held, from its "heap:"
lines: a leak grows the heap in use, the allocator's high water only what is held and resident.
Python 3 standard library plus matplotlib (Debian's python3-matplotlib) for the plot."""

import argparse
import csv
import os
import re
import sys
import time
from collections import defaultdict


def slope(xs, ys):
    """Least-squares slope of ys over xs (0 with fewer than two distinct xs)."""
    n = len(xs)
    if n < 2:
        return 0.0
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx > 0 else 0.0


HEAP_LINE = re.compile(r"^\[(\d\d):(\d\d):(\d\d(?:\.\d+)?)\] .*heap: ([\d.]+) MB in use, "
                       r"([\d.]+) MB held; ([\d.]+) MB of freed heap released")


def heap_samples(path, t0):
    """[(seconds since t0, MB in use, MB held, MB released)] from a client's heap lines (their
    times are local times of day, as spdlog writes them)."""
    start = time.localtime(t0)
    start_tod = start.tm_hour * 3600 + start.tm_min * 60 + start.tm_sec + (t0 % 1)
    out = []
    try:
        with open(path, errors="replace") as f:
            for line in f:
                m = HEAP_LINE.match(line)
                if m:
                    tod = int(m[1]) * 3600 + int(m[2]) * 60 + float(m[3])
                    out.append(((tod - start_tod) % 86400, float(m[4]), float(m[5]), float(m[6])))
    except OSError:
        pass
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--samples", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--warmup", type=float, default=1.0, help="minutes left out of the checks")
    ap.add_argument("--max-slope", type=float, default=1.0, help="MB per hour")
    ap.add_argument("--minutes", type=float, default=0)
    ap.add_argument("--actions", default="")
    ap.add_argument("--master-exit", type=int, default=0)
    ap.add_argument("--clients-left-running", type=int, default=0)
    ap.add_argument("--stats-ok", type=int, default=1)
    ap.add_argument("--stats-frames", type=int, default=0)
    ap.add_argument("--t0", type=float, default=0, help="the samples' time 0 (seconds since the epoch)")
    ap.add_argument("--heap-log", action="append", default=[], metavar="NAME=FILE")
    a = ap.parse_args()

    rows = defaultdict(list)  # (name, pid) -> [(seconds, rss_kb, fds, threads)]
    frames = []  # (seconds, frames_done)
    with open(a.samples, newline="") as f:
        for r in csv.DictReader(f):
            t = float(r["seconds"])
            rows[(r["name"], r["pid"])].append((t, int(r["rss_kb"]), int(r["fds"]), int(r["threads"])))
            if r["name"] == "master" and r["frames_done"]:
                frames.append((t, int(r["frames_done"])))
    if not rows:
        print("soak: no samples", file=sys.stderr)
        return 1
    end = max(s[-1][0] for s in rows.values())
    warm = a.warmup * 60
    after = end - warm
    failures = []
    table = ["| process | samples | lived (min) | RSS after warm-up (MB) | RSS at end (MB) | "
             "slope after warm-up (MB/h) | fds (min-max) | threads (min-max) | checked |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---|"]
    order = sorted(rows, key=lambda k: (k[0] != "master", not k[0].startswith("steady"),
                                        rows[k][0][0], k[0]))
    for key in order:
        name, pid = key
        s = rows[key]
        w = [x for x in s if x[0] >= warm]
        lived = (s[-1][0] - s[0][0]) / 60
        long_lived = len(w) >= 3 and (w[-1][0] - w[0][0]) >= 0.5 * after
        mb_per_hour = slope([x[0] / 3600 for x in w], [x[1] / 1024 for x in w]) if len(w) >= 2 else 0.0
        checked = []
        if long_lived:
            checked.append("memory")
            if mb_per_hour > a.max_slope:
                failures.append(f"{name} (pid {pid}): memory grows {mb_per_hour:.2f} MB/h after the "
                                f"warm-up (bound {a.max_slope} MB/h)")
        if long_lived and (name == "master" or name.startswith("steady")):
            checked.append("fds, threads")
            cut = len(w) * 2 // 3
            for col, what in ((2, "descriptors"), (3, "threads")):
                first, last = max(x[col] for x in w[:cut]), max(x[col] for x in w[cut:])
                if last > first:
                    failures.append(f"{name} (pid {pid}): {what} grow: {first} at most in the first "
                                    f"two thirds after the warm-up, {last} in the last third")
        table.append(f"| {name} ({pid}) | {len(s)} | {lived:.1f} | "
                     f"{(w[0][1] / 1024 if w else float('nan')):.1f} | {s[-1][1] / 1024:.1f} | "
                     f"{mb_per_hour:+.3f} | {min(x[2] for x in s)}-{max(x[2] for x in s)} | "
                     f"{min(x[3] for x in s)}-{max(x[3] for x in s)} | {', '.join(checked) or '-'} |")
    if not any(k[0] == "master" and len([x for x in rows[k] if x[0] >= warm]) >= 3 for k in rows):
        failures.append("fewer than 3 samples of the master after the warm-up: nothing checked")
    if a.master_exit != 0:
        failures.append(f"the master exited with {a.master_exit}")
    if a.clients_left_running:
        failures.append(f"{a.clients_left_running} clients still ran 10 s after the master ended")
    if not a.stats_ok:
        failures.append("--stats-json is not valid JSON")

    fps = [(t1, (f1 - f0) / (t1 - t0)) for (t0, f0), (t1, f1) in zip(frames, frames[1:]) if t1 > t0]
    total_frames = frames[-1][1] if frames else 0
    heaps = {}
    for spec in a.heap_log:
        name, _, path = spec.partition("=")
        heaps[name] = heap_samples(path, a.t0)
    heap_table = ["| client | heap lines | in use after warm-up (MB) | in use at end (MB) | "
                  "in use slope (MB/h) | held slope (MB/h) | released in all (MB) |",
                  "|---|---:|---:|---:|---:|---:|---:|"]
    for name, h in heaps.items():
        w = [x for x in h if x[0] >= warm]
        if len(w) < 2:
            heap_table.append(f"| {name} | {len(h)} | - | - | - | - | - |")
            continue
        hours = [x[0] / 3600 for x in w]
        heap_table.append(f"| {name} | {len(h)} | {w[0][1]:.1f} | {w[-1][1]:.1f} | "
                          f"{slope(hours, [x[1] for x in w]):+.3f} | "
                          f"{slope(hours, [x[2] for x in w]):+.3f} | {sum(x[3] for x in h):.1f} |")
    heap_lines = (["", "Heap of the steady clients (glibc's figures, logged every 20 s after the "
                   "client gives its freed heap back; slopes after the warm-up):", "", *heap_table]
                  if heaps else [])

    lines = [f"Soak of {a.minutes:g} min ({end / 60:.1f} min sampled, warm-up {a.warmup:g} min "
             f"left out of the checks): {total_frames} frames "
             f"({total_frames / end if end else 0:.1f} per second on average), "
             f"{a.stats_frames} in --stats-json; master exit {a.master_exit}.",
             "", f"Actions: {a.actions}.", "", *table, *heap_lines, "",
             "Result: " + ("all checks passed." if not failures else "FAILED:"),
             *[f"- {f}" for f in failures]]
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, "summary.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("soak: no matplotlib (python3-matplotlib): no plot", file=sys.stderr)
        return 1 if failures else 0
    fig, ax = plt.subplots(3, 1, figsize=(9, 9), sharex=True)
    for key in order:
        name, pid = key
        s = rows[key]
        label = name if name == "master" or name.startswith("steady") else None
        style = dict(lw=1.2) if label else dict(lw=0.5, color="0.7")
        ax[0].plot([x[0] / 60 for x in s], [x[1] / 1024 for x in s], label=label, **style)
        ax[1].plot([x[0] / 60 for x in s], [x[2] for x in s], label=label, **style)
    for name, h in heaps.items():
        ax[0].plot([x[0] / 60 for x in h], [x[1] for x in h], ls="--", lw=1,
                   label=f"{name}: heap in use")
    ax[2].plot([t / 60 for t, _ in fps], [v for _, v in fps], lw=0.8)
    for axis in ax:
        axis.axvline(a.warmup, color="r", ls=":", lw=0.8)
    ax[0].set_ylabel("memory (MB)")
    ax[0].legend(fontsize=8)
    ax[1].set_ylabel("open descriptors")
    ax[2].set_ylabel("frames per second")
    ax[2].set_xlabel("minutes (grey: churning clients; dotted: end of warm-up)")
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "soak.png"), dpi=90)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
