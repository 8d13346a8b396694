#!/usr/bin/python3
"""Writes docs/perf/network.json, docs/perf/network.png and the generated 'network' block of
docs/PERFORMANCE.md from the runs of scripts/bench_network.sh (its --help says what they are).

Usage: network_report.py OUT RATES REPLAY_RATES REPLAY_CLIENTS CLIENTS FRAMES REPLAY_FRAMES SECONDS
"""
import datetime
import json
import os
import re
import statistics
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from perf_report import steady_fps  # noqa: E402  (the same frame-line timing as section 4)

SIZES = ("640x480", "1280x960")
TARGETS = (5, 10, 20, 30)  # frame rates the "link needed" lines answer for


def load(out, name, skip=0):
    """fps and wire bytes per pixel of one run; with skip, both from frame `skip` on."""
    with open(os.path.join(out, name + ".json")) as f:
        s = json.load(f)
    frames = [fr for fr in s["frames"] if fr["index"] >= skip]
    bpp = statistics.mean(fr["wire_bytes_per_pixel"] for fr in frames)
    fps = steady_fps(os.path.join(out, name + ".log"), skip) if skip else s["fps"]
    # What the uplink carried over the whole run against the tiles' payload: TCP/IP and
    # Ethernet headers, the protocol's own messages, retransmissions.
    with open(os.path.join(out, name + ".uplink-bytes")) as f:
        overhead = int(f.read()) / sum(fr["wire_bytes"] for fr in s["frames"])
    return {"fps": fps, "bytes_per_pixel": bpp, "uplink_overhead": overhead}


def mbit(run, size, link=False):
    """Payload Mbit/s of a run, or with link the Mbit/s on the master's uplink."""
    w, h = map(int, size.split("x"))
    return (run["bytes_per_pixel"] * w * h * run["fps"] * 8e-6 *
            (run["uplink_overhead"] if link else 1))


def main():
    out, rates, replay_rates, replay_clients = sys.argv[1], *(a.split() for a in sys.argv[2:5])
    clients, frames, replay_frames, seconds = map(int, sys.argv[5:9])
    # Replaying clients render each tile the first time they are given it, and the pipeline
    # fills: the first quarter of a replay run is left out of its rate.
    skip = replay_frames // 4
    results = {}
    for size in SIZES:
        r = {"unlimited": load(out, f"{size}-unlimited")}
        for rate in rates:
            r[f"client-{rate}"] = load(out, f"{size}-client-{rate}")
            r[f"uplink-{rate}"] = load(out, f"{size}-uplink-{rate}")
        for n in replay_clients:
            for rate in replay_rates + ["0"]:
                run = load(out, f"{size}-replay{n}-uplink-{rate}", skip)
                run["mbit_per_second"] = mbit(run, size)
                run["link_mbit_per_second"] = mbit(run, size, link=True)
                r[f"replay{n}-uplink-{rate}"] = run
        results[size] = r
    with open("docs/perf/network.json", "w") as f:
        json.dump(results, f, indent=1)
    plot(results, rates, replay_rates, replay_clients, clients)

    rev = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                         text=True).stdout.strip()
    L = [f"Measured on {datetime.date.today()} by `scripts/bench_network.sh` ({seconds // 60} min "
         f"{seconds % 60} s), build `{rev}`, on this 2-core machine: the default scene, paper "
         "settings, the master and each client on its own host made of a network namespace, hosts "
         "joined by a bridge, links limited by tc's token bucket filter. No latency is emulated "
         "(this kernel has no netem).", "",
         f"**Rendering clients** ({clients} clients, one thread each, {frames} frames a run). "
         "'Each client' limits every client's own link; 'master uplink' limits what reaches the "
         "master, shared by all clients.", "",
         "| image | link limit | each client: fps | master uplink: fps | wire bytes / pixel |",
         "|---|---|---|---|---|"]
    for size, r in results.items():
        u = r["unlimited"]
        L.append(f"| {size} | none | {u['fps']:.2f} | {u['fps']:.2f} | {u['bytes_per_pixel']:.2f} |")
        for rate in rates:
            c, m = r[f"client-{rate}"], r[f"uplink-{rate}"]
            L.append(f"| {size} | {rate} Mbit/s | {c['fps']:.2f} | {m['fps']:.2f} | "
                     f"{c['bytes_per_pixel']:.2f} |")
    L.append("")
    for size, r in results.items():
        u = r["unlimited"]["fps"]
        enough = [rate for rate in rates if r[f"uplink-{rate}"]["fps"] >= 0.95 * u]
        need = f"{enough[0]} Mbit/s was enough" if enough else "none of the rates tried was enough"
        L.append(f"- {size}: at {u:.2f} fps the clients sent {mbit(r['unlimited'], size):.1f} "
                 f"Mbit/s in all ({mbit(r['unlimited'], size):.0f} % of a 100 Mbit/s link); "
                 f"for the master's uplink {need} to keep 95 % of the unlimited frame rate.")
    L += ["", f"**The link a master needs for N clients** ({replay_frames} frames a run, the "
          f"first {skip} left out). Replaying clients (`igi-client --replay`) resend each tile's "
          "first result, so they stand for clients as fast as one likes and the master's uplink "
          "(or the master itself) is what limits the frame rate. Each cell: fps, then the Mbit/s "
          "of tile payload and of everything the uplink carried (its own byte count: headers and "
          "protocol messages included).", "",
          "| image | master uplink | " + " | ".join(f"{n} client{'s' if n != '1' else ''}"
                                                  for n in replay_clients) + " |",
          "|---|---|" + "---|" * len(replay_clients)]
    for size, r in results.items():
        for rate in replay_rates + ["0"]:
            cells = [r[f"replay{n}-uplink-{rate}"] for n in replay_clients]
            label = f"{rate} Mbit/s" if rate != "0" else "none"
            L.append(f"| {size} | {label} | " + " | ".join(
                f"{c['fps']:.1f} fps ({c['mbit_per_second']:.0f}; {c['link_mbit_per_second']:.0f})"
                for c in cells) + " |")
    L.append("")
    for size, r in results.items():
        carried = {rate: max(r[f"replay{n}-uplink-{rate}"]["fps"] for n in replay_clients)
                   for rate in replay_rates + ["0"]}
        answers = []
        for target in TARGETS:
            ok = [rate for rate in replay_rates if carried[rate] >= target]
            if ok:
                answers.append(f"{target} fps: {ok[0]} Mbit/s")
            elif carried["0"] >= target:
                answers.append(f"{target} fps: more than {replay_rates[-1]} Mbit/s")
            else:
                answers.append(f"{target} fps: not reached here (the master stops at "
                               f"{carried['0']:.1f} fps without a limit)")
        L.append(f"- {size}, the smallest uplink tried that carried: " + "; ".join(answers) + ".")
    if {"100", "1000"} <= set(replay_rates):
        best = {rate: max(results["640x480"][f"replay{n}-uplink-{rate}"]["fps"]
                          for n in replay_clients) for rate in ("100", "1000", "0")}
        L.append(f"- The paper's master handled about 1.5 M pixels/s (5 fps at 640x480) behind a "
                 "Gigabit uplink, its clients on 100 Mbit/s. With this wire format a 100 Mbit/s "
                 f"uplink carried {best['100']:.1f} fps at 640x480 "
                 f"({best['100'] * 0.3072:.1f} M pixels/s), so the paper's rate would have fit in "
                 f"it; Gigabit carried {best['1000']:.1f} fps, against {best['0']:.1f} fps with no "
                 "limit (the master's and this machine's own ceiling).")
    L += ["", "![fps against link rate](perf/network.png)"]
    block = "\n".join(L)
    doc = "docs/PERFORMANCE.md"
    text = open(doc, encoding="utf-8").read()
    pat = re.compile(r"(<!-- BEGIN GENERATED network -->\n).*?(\n?<!-- END GENERATED network -->)",
                     re.S)
    if not pat.search(text):
        sys.exit(f"{doc} has no <!-- BEGIN GENERATED network --> block")
    text = pat.sub(lambda m: m.group(1) + block + "\n" + m.group(2).lstrip("\n"), text)
    open(doc, "w", encoding="utf-8").write(text)
    print(block)


def plot(results, rates, replay_rates, replay_clients, clients):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    # "none" is drawn one decade right of the highest rate tried.
    top = max(int(x) for x in rates + replay_rates) * 10
    fig, axes = plt.subplots(1, len(SIZES), figsize=(10, 4), sharey=False)
    for ax, size in zip(axes, SIZES):
        r = results[size]

        def line(keys, label, style):
            xs = [top if k == "unlimited" else int(k.rsplit("-", 1)[1]) or top for k in keys]
            ax.plot(xs, [r[k]["fps"] for k in keys], style, label=label)

        line([f"client-{x}" for x in rates] + ["unlimited"],
             f"{clients} rendering clients, each client's link", "o-")
        line([f"uplink-{x}" for x in rates] + ["unlimited"],
             f"{clients} rendering clients, master uplink", "s--")
        for n in replay_clients:
            line([f"replay{n}-uplink-{x}" for x in replay_rates + ["0"]],
                 f"{n} replaying, master uplink", "^:")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ticks = sorted({int(x) for x in rates + replay_rates}) + [top]
        ax.set_xticks(ticks)
        ax.set_xticklabels([str(t) for t in ticks[:-1]] + ["none"])
        ax.set_xlabel("link rate (Mbit/s)")
        ax.set_ylabel("frames per second")
        ax.set_title(size)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig("docs/perf/network.png", dpi=100)


if __name__ == "__main__":
    main()
