#!/usr/bin/env python3
"""Turns the raw outputs of scripts/bench_performance.sh into docs/PERFORMANCE.md, a summary
docs/perf/results.json and, when matplotlib is there, docs/perf/scaling.png.

Standard library only, except matplotlib for the plot (Debian's python3-matplotlib: run with
/usr/bin/python3). Usage: perf_report.py --raw out/perf --doc docs/PERFORMANCE.md --command CMD
"""
import argparse
import glob
import json
import os
import re
import sys

# The paper's figures (Wald et al. 2002, section 5; /work/shared/DESIGN.md).
PAPER_CEILING_MPX = 1.5
PAPER_CORNELL_FPS = 3.3  # 8 clients, AthlonMP 1800+, ~0.5 M rays/s each
PAPER_RAYS_PER_CLIENT = 0.5e6
CEILING_SKIP = 4  # frames of a replay run left out of its ceiling

SCENE_LABELS = {
    "cornell-default": "default (`scenes/cornell/cornell.json`)",
    "CornellBox-Original": "CornellBox-Original.obj",
    "CornellBox-Sphere": "CornellBox-Sphere.obj",
    "CornellBox-Mirror": "CornellBox-Mirror.obj",
    "interior-glossy": "glossy interior, 96 lights (`scenes/interior/glossy.json`)",
    "interior-sculptures": "interior with sculptures, 96 lights (`scenes/interior/sculptures.json`)",
    "sponza-arcades": "Sponza arcades, 120 lights (`scenes/sponza/arcades.json`)",
    "interior-glossy-accumulated": "glossy interior, 96 lights, accumulated frames",
    "interior-sculptures-accumulated": "interior with sculptures, 96 lights, accumulated frames",
    "sponza-arcades-accumulated": "Sponza arcades, 120 lights, accumulated frames",
}
# Section 1's many-light scenes (issue 36), summarized apart from the Cornell boxes: first
# frames after a change (igi-bench's default), and accumulated ones (--accumulated).
MANY_LIGHTS_FIRST = ("interior-glossy", "interior-sculptures", "sponza-arcades")
MANY_LIGHTS_ACCUMULATED = tuple(f"{n}-accumulated" for n in MANY_LIGHTS_FIRST)
MANY_LIGHTS = MANY_LIGHTS_FIRST + MANY_LIGHTS_ACCUMULATED
SCENE_ORDER = list(SCENE_LABELS)


def median(values):
    v = sorted(values)
    n = len(v)
    return v[n // 2] if n % 2 else 0.5 * (v[n // 2 - 1] + v[n // 2])


def load_json(path):
    with open(path) as f:
        return json.load(f)


def read_meta(path):
    meta = {}
    with open(path) as f:
        for line in f:
            if "=" in line:
                key, value = line.rstrip("\n").split("=", 1)
                meta[key] = value
    return meta


def scene_key(name):
    return (SCENE_ORDER.index(name) if name in SCENE_ORDER else len(SCENE_ORDER), name)


def fmt(x, digits=2):
    if x is None:
        return "n/a"
    return f"{x:.{digits}f}"


def table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "|".join("---:" if i else "---" for i in range(len(header))) + "|"]
    out += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(out)


# --- per-run summaries from a master's --stats-json ------------------------------------------


FRAME_LINE = re.compile(r"^\[(\d\d):(\d\d):(\d\d(?:\.\d+)?)\] \[master\] \[info\] frame +(\d+):")


def steady_fps(log_path, skip=0):
    """Frames per second from frame `skip` shown to the last frame shown, from the master's log
    (one line per frame composited, with a time of day): leaves out start-up and the pipeline
    fill of the first frames. None if the log has too few frame lines."""
    if not log_path or not os.path.exists(log_path):
        return None
    times = []
    with open(log_path, errors="replace") as f:
        for line in f:
            m = FRAME_LINE.match(line)
            if m:
                t = int(m[1]) * 3600 + int(m[2]) * 60 + float(m[3])
                if times and t < times[-1][1]:
                    t += 86400  # past midnight
                times.append((int(m[4]), t))
    times = [t for t in times if t[0] >= skip]
    if len(times) < 2 or times[-1][1] <= times[0][1]:
        return None
    return (times[-1][0] - times[0][0]) / (times[-1][1] - times[0][1])


def summarize_stats(stats, log_path=None, skip=0):
    """Frame rate, rays and the frame-time split of one igi-master run."""
    frames = stats["frames"]
    clients = stats["clients"]
    n = len(frames)
    seconds = stats["seconds"]
    pixels = sum(f["pixels"] for f in frames)
    rays = sum(f["rays"] for f in frames)
    shadow = sum(f["shadow_rays"] for f in frames)
    wire = sum(f["wire_bytes"] for f in frames)
    decode = sum(f["decode_seconds"] for f in frames)
    composite = sum(f["composite_seconds"] for f in frames)
    busy = [c["busy_seconds"] for c in clients]
    idle = [c["idle_seconds"] for c in clients]
    return {
        "frames": n,
        "seconds": seconds,
        "fps": stats["fps"],
        "steady_fps": steady_fps(log_path, skip),
        "frame_ms": 1000.0 * seconds / n if n else None,
        "width": int(stats["session"]["width"]),
        "height": int(stats["session"]["height"]),
        "pixels_per_second": pixels / seconds if seconds else None,
        "rays_per_second": rays / seconds if seconds else None,
        "shadow_rays_per_pixel": shadow / pixels if pixels else None,
        "rays_per_pixel": rays / pixels if pixels else None,
        "wire_bytes_per_pixel": wire / pixels if pixels else None,
        "wire_bytes_per_second": wire / seconds if seconds else None,
        "clients": len(clients),
        "client_threads": [c["threads"] for c in clients],
        # Per frame, in wall seconds of an average client: rendering, and waiting (for tiles to
        # arrive, for results to leave, for the master; on loopback this is the "network").
        "client_busy_ms": 1000.0 * sum(busy) / len(busy) / n if busy and n else None,
        "client_idle_ms": 1000.0 * sum(idle) / len(idle) / n if idle and n else None,
        # Master CPU time per frame: decoding tiles (summed over its threads) and compositing
        # (discontinuity buffer + accumulation, one thread).
        "master_decode_ms": 1000.0 * decode / n if n else None,
        "master_composite_ms": 1000.0 * composite / n if n else None,
        "master_decode_ns_per_pixel": 1e9 * decode / pixels if pixels else None,
        "distinct_sets_per_client_frame": (
            sum(c["distinct_sets_per_frame"] for c in clients) / len(clients) if clients else None
        ),
        "duplicate_tiles": sum(f["duplicate_tiles"] for f in frames),
        "rays_per_second_per_client": rays / seconds / len(clients) if seconds and clients else None,
    }


def parse_cgroup_stats(path):
    """Lines 'name nr_periods P nr_throttled T throttled_time NS ...' -> summary."""
    periods = throttled = 0
    groups = 0
    if not os.path.exists(path):
        return None
    with open(path) as f:
        for line in f:
            words = line.split()
            values = dict(zip(words[1::2], words[2::2]))
            periods += int(values.get("nr_periods", 0))
            throttled += int(values.get("nr_throttled", 0))
            groups += 1
    return {"groups": groups, "periods": periods, "throttled": throttled,
            "throttled_share": throttled / periods if periods else None}


def parse_stages(path):
    """igi-composite-bench's output: ns/pixel by stage and the ceiling."""
    text = open(path).read()
    m = re.search(r"(\d+) x (\d+), (\d+) frames", text)
    if not m:
        return None
    out = {"width": int(m[1]), "height": int(m[2]), "frames": int(m[3]), "ns": {}}
    for name, ns in re.findall(r"^(.+?)\s+([\d.]+) ns/pixel$", text, re.M):
        out["ns"][name.strip()] = float(ns)
    m = re.search(r"master ceiling: ([\d.]+) M pixels/s", text)
    out["mpx"] = float(m[1]) if m else None
    return out


def parse_codec(path):
    text = open(path).read()
    out = {"text": text.strip()}
    m = re.search(r"size: ([\d.]+) bytes/pixel on the wire \(zstd frame ([\d.]+), quantized before zstd (\d+), as floats (\d+)\)", text)
    if m:
        out.update(wire=float(m[1]), zstd=float(m[2]), quantized=int(m[3]), floats=int(m[4]))
    m = re.search(r"decode: ([\d.]+) M pixels/s per core \(([\d.]+) ns/pixel; zstd alone ([\d.]+) ns/pixel\)", text)
    if m:
        out.update(decode_mpx=float(m[1]), decode_ns=float(m[2]), zstd_ns=float(m[3]))
    m = re.search(r"encode: ([\d.]+) M pixels/s per core \(([\d.]+) ns/pixel\)", text)
    if m:
        out.update(encode_mpx=float(m[1]), encode_ns=float(m[2]))
    planes = re.findall(r"(\w+) ([\d.]+) \(of (\d+)\)", text)
    if planes:
        out["planes"] = {name: {"compressed": float(c), "quantized": int(q)} for name, c, q in planes}
    return out


# --- the document ------------------------------------------------------------------------------


def end_to_end_runs(folder):
    """The summaries of section 2's runs in `folder` (NAME-cCLIENTS.json and .log), in order."""
    runs = []
    for path in sorted(glob.glob(os.path.join(folder, "*.json"))):
        name, clients = re.match(r"(.*)-c(\d+)\.json$", os.path.basename(path)).groups()
        s = summarize_stats(load_json(path), path[:-5] + ".log")
        s["name"] = name
        runs.append(s)
    runs.sort(key=lambda s: (scene_key(s["name"]), s["clients"]))
    return runs


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--raw", required=True)
    ap.add_argument("--doc", required=True)
    ap.add_argument("--command", default="scripts/bench_performance.sh")
    args = ap.parse_args()
    raw = args.raw
    doc = args.doc
    perf_dir = os.path.join(os.path.dirname(os.path.abspath(doc)), "perf")
    os.makedirs(perf_dir, exist_ok=True)
    meta = read_meta(os.path.join(raw, "meta.env"))
    cmd = args.command
    results = {"meta": meta}

    # 1. igi-bench
    # Repeated runs of one scene and thread count: the median of each figure, and of the ratio
    # (taken within each run, whose two phases ran back to back).
    reps = {}
    for path in sorted(glob.glob(os.path.join(raw, "bench", "*.json"))):
        name, threads = re.match(r"(.*)-t(\d+)-r\d+\.json$", os.path.basename(path)).groups()
        reps.setdefault((name, int(threads)), []).append(load_json(path))
    bench = []
    for (name, threads), runs in reps.items():
        b = dict(runs[0])
        for key in ("embree_occluded1_rays_per_second", "embree_occluded8_rays_per_second",
                    "embree_occluded16_rays_per_second", "client_rays_per_second",
                    "client_shadow_rays_per_second"):
            b[key] = median([r.get(key, float("nan")) for r in runs])
        # Against rtcOccluded16 per CPU second: the raw and client phases' CPU time, which the
        # machine's other users disturb less than wall time.
        b["ratio_shadow_16"] = median([r.get("client_shadow_rays_over_embree_occluded16_cpu", float("nan"))
                                       for r in runs])
        b["ratio_shadow_8_cpu"] = median([r["client_shadow_rays_per_cpu_second"] / r["embree_occluded8_rays_per_cpu_second"]
                                          if "client_shadow_rays_per_cpu_second" in r else float("nan") for r in runs])
        b["ratio_16_8"] = median([r["embree_occluded16_rays_per_cpu_second"] / r["embree_occluded8_rays_per_cpu_second"]
                                  if "embree_occluded16_rays_per_cpu_second" in r else float("nan") for r in runs])
        b["ratio_all"] = median([r["client_rays_per_second"] / r["embree_occluded1_rays_per_second"] for r in runs])
        b["ratio_shadow"] = median([r["client_shadow_rays_per_second"] / r["embree_occluded1_rays_per_second"] for r in runs])
        b["ratio_packets"] = median([r["embree_occluded8_rays_per_second"] / r["embree_occluded1_rays_per_second"] for r in runs])
        b["ratio_shadow_packets"] = median([r["client_shadow_rays_per_second"] / r["embree_occluded8_rays_per_second"] for r in runs])
        b["ratio_all_range"] = [min(r["client_rays_per_second"] / r["embree_occluded1_rays_per_second"] for r in runs),
                                max(r["client_rays_per_second"] / r["embree_occluded1_rays_per_second"] for r in runs)]
        b["repeats"] = len(runs)
        b["name"] = name
        bench.append(b)
    bench.sort(key=lambda b: (scene_key(b["name"]), b["threads"]))
    results["bench"] = bench

    # 2. end-to-end frame rate, at 640 x 480 and at full HD
    fps = end_to_end_runs(os.path.join(raw, "fps"))
    results["fps"] = fps
    fullhd = end_to_end_runs(os.path.join(raw, "fullhd"))
    results["fullhd"] = fullhd

    # 3. scaling
    scaling = []
    for path in glob.glob(os.path.join(raw, "scaling", "n*.json")):
        n = int(re.match(r"n(\d+)\.json$", os.path.basename(path))[1])
        s = summarize_stats(load_json(path), os.path.join(raw, "scaling", f"n{n}-master.log"), 1)
        s["n"] = n
        s["cgroups"] = parse_cgroup_stats(os.path.join(raw, "scaling", f"n{n}-cgroups.txt"))
        scaling.append(s)
    scaling.sort(key=lambda s: s["n"])
    # Speed-up from the steady frame rate (the whole run's rate where the log has no frames).
    for s in scaling:
        s["rate"] = s["steady_fps"] or s["fps"]
    base = next((s for s in scaling if s["n"] == 1), None)
    # The uncapped rate of one client thread on this scene (section 1), for the share used.
    one_thread = next((b for b in bench if b["name"] == "cornell-default" and b["threads"] == 1), None)
    for s in scaling:
        if base and base["rate"]:
            s["speedup"] = s["rate"] / base["rate"]
            s["efficiency"] = s["speedup"] / s["n"]
        else:
            s["speedup"] = s["efficiency"] = None
        s["share_used"] = (
            s["rays_per_second_per_client"] / (share(meta) * one_thread["client_rays_per_second"])
            if one_thread and share(meta) else None)
    results["scaling"] = scaling

    # 4. master ceiling
    ceiling = []
    for path in glob.glob(os.path.join(raw, "ceiling", "*.json")):
        t, w, h = map(int, re.match(r"t(\d+)-(\d+)x(\d+)\.json$", os.path.basename(path)).groups())
        # The first frames are really rendered (a replaying client renders a tile the first
        # time it is asked for it, and two frames are in flight): leave out CEILING_SKIP.
        run = summarize_stats(load_json(path), path[:-5] + ".log", CEILING_SKIP)
        entry = {"threads": t, "width": w, "height": h, "run": run}
        entry["mpx_per_second"] = run["steady_fps"] * w * h / 1e6 if run["steady_fps"] else None
        entry["mpx_per_second_whole_run"] = run["pixels_per_second"] / 1e6
        ceiling.append(entry)
    ceiling.sort(key=lambda c: (c["width"], c["threads"]))
    results["ceiling"] = ceiling
    stages = [parse_stages(p) for p in sorted(glob.glob(os.path.join(raw, "ceiling", "stages-*.txt")))]
    stages = sorted((st for st in stages if st), key=lambda st: st["width"])
    results["ceiling_stages"] = stages

    # 5. codec
    codec_path = os.path.join(raw, "codec", "codec.txt")
    codec = parse_codec(codec_path) if os.path.exists(codec_path) else None
    results["codec"] = codec

    with open(os.path.join(perf_dir, "results.json"), "w") as f:
        json.dump(results, f, indent=1, sort_keys=True)

    plot = make_plot(scaling, meta, os.path.join(perf_dir, "scaling.png"))
    # Rendered before the file is opened for writing: render_doc keeps the blocks other scripts
    # generate (section 6) by reading them from the document it replaces.
    text = render_doc(meta, cmd, bench, fps, scaling, ceiling, codec, plot, doc, perf_dir, stages,
                      fullhd)
    lost = dropped_blocks(doc, text)
    if lost:
        # A block that another script generated (or that was written by hand) exists only in
        # this document: writing over it would lose its measurements for good.
        sys.exit(f"perf_report.py: {doc} has generated blocks that the new text would drop: "
                 f"{', '.join(lost)}; render_doc must keep each (generated_block)")
    with open(doc, "w") as f:
        f.write(text)
    print(f"wrote {doc} and {perf_dir}/", file=sys.stderr)


def make_plot(scaling, meta, path):
    if len(scaling) < 2:
        return None
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        import matplotlib.ticker
    except ImportError:
        print("matplotlib is missing: no plot (install python3-matplotlib)", file=sys.stderr)
        return None
    ns = [s["n"] for s in scaling]
    fps = [s["rate"] for s in scaling]
    base = scaling[0]["rate"] / scaling[0]["n"]
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    ax[0].plot(ns, [base * n for n in ns], "--", color="gray", label="linear (ideal)")
    ax[0].plot(ns, fps, "o-", label="measured")
    ax[0].set_xscale("log", base=2)
    ax[0].set_yscale("log", base=2)
    ax[0].set_xticks(ns)
    ax[0].set_xticklabels([str(n) for n in ns])
    ax[0].set_xlabel("clients (each capped at %.2f%% of a core)" % (100 * share(meta)))
    ax[0].set_ylabel("frames per second (steady)")
    ax[0].set_title("fps, %sx%s, paper settings" % (meta.get("scale_width"), meta.get("scale_height")))
    ax[0].yaxis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
    ax[0].legend()
    ax[0].grid(True, which="both", alpha=0.3)
    ax[1].plot(ns, [100 * (s["efficiency"] or 0) for s in scaling], "o-")
    ax[1].axhline(100, color="gray", ls="--")
    ax[1].set_xscale("log", base=2)
    ax[1].set_xticks(ns)
    ax[1].set_xticklabels([str(n) for n in ns])
    ax[1].set_ylim(0, max(120, 10 + max(100 * (s["efficiency"] or 0) for s in scaling)))
    ax[1].set_xlabel("clients")
    ax[1].set_ylabel("parallel efficiency (%)")
    ax[1].set_title("fps(N) / (N fps(1))")
    ax[1].grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    return path


def share(meta):
    try:
        return int(meta["scale_quota_us"]) / int(meta["scale_period_us"])
    except (KeyError, ValueError, ZeroDivisionError):
        return 0.0


def generated_block(doc, key):
    """The body of the document's <!-- BEGIN GENERATED key --> block, if it has one."""
    try:
        with open(doc, encoding="utf-8") as f:
            text = f.read()
    except OSError:
        return None
    m = re.search(rf"<!-- BEGIN GENERATED {re.escape(key)} -->\n(.*?)\n?<!-- END GENERATED "
                  rf"{re.escape(key)} -->", text, re.S)
    return m.group(1) if m else None


def dropped_blocks(doc, text):
    """The keys of the <!-- BEGIN GENERATED key --> blocks of the document that text lacks."""
    try:
        with open(doc, encoding="utf-8") as f:
            old = f.read()
    except OSError:
        return []
    pattern = re.compile(r"<!-- BEGIN GENERATED ([^ ]+) -->")
    return sorted(set(pattern.findall(old)) - set(pattern.findall(text)))


FPS_HEADER = ["scene", "clients", "threads", "fps", "ms / frame", "Mrays/s", "shadow rays / px",
              "client render ms / frame", "client waiting ms / frame", "master decode ms / frame",
              "master composite ms / frame", "wire B / px", "distinct k / client / frame"]


def fps_rows(runs):
    """The rows of an end-to-end table (section 2), one per run."""
    rows = []
    for s in runs:
        busy, idle = s["client_busy_ms"], s["client_idle_ms"]
        frame = s["frame_ms"]
        rows.append([
            SCENE_LABELS.get(s["name"], s["name"]), s["clients"], "+".join(map(str, s["client_threads"])),
            fmt(s["fps"], 2), fmt(frame, 0), fmt(s["rays_per_second"] / 1e6, 1),
            fmt(s["shadow_rays_per_pixel"], 1),
            f"{fmt(busy, 0)} ({fmt(100 * busy / frame, 0)} %)",
            f"{fmt(idle, 0)} ({fmt(100 * idle / frame, 0)} %)",
            fmt(s["master_decode_ms"], 1), fmt(s["master_composite_ms"], 1),
            fmt(s["wire_bytes_per_pixel"], 2), fmt(s["distinct_sets_per_client_frame"], 1),
        ])
    return rows


def render_doc(meta, cmd, bench, fps, scaling, ceiling, codec, plot, doc, perf_dir, stages=(),
               fullhd=()):
    rel_perf = os.path.relpath(perf_dir, os.path.dirname(os.path.abspath(doc)))
    quick = meta.get("quick") == "1"
    L = []
    w = L.append
    w("# Performance")
    w("")
    w("<!-- Generated by scripts/perf_report.py from a run of scripts/bench_performance.sh; "
      "edit those, not this file. -->")
    w("")
    w(f"Measured on {meta.get('date', '?')} by `{cmd}` "
      f"({int(meta.get('run_seconds', 0)) // 60} min {int(meta.get('run_seconds', 0)) % 60} s), "
      f"build `{meta.get('git_rev', '?')}`" + (f" with {meta['git_dirty']} uncommitted files" if meta.get("git_dirty", "0") not in ("", "0") else "") + ".")
    if quick:
        w("")
        w("**This is a `--quick` smoke run: few frames, small images, few clients. "
          "Its figures are not the ones to quote.**")
    w("")
    w("Every section below is regenerated by the one command `scripts/bench_performance.sh` "
      "(about 10 minutes; `--quick` for a one- or two-minute smoke run). It builds with "
      "`scripts/setup.sh` unless `IGI_BUILD=/path/to/build` names a build to use, keeps raw "
      "outputs (master statistics JSON, logs) in `out/perf/`, and writes this file, "
      f"`{rel_perf}/results.json` (every figure below, and more) and `{rel_perf}/scaling.png`.")
    w("")
    w("## The machine, and how much to trust these numbers")
    w("")
    w(table(["", ""], [
        ["CPU", f"{meta.get('cpu_model', '?')}, `nproc` = {meta.get('nproc', '?')}, "
                f"AVX2: {meta.get('cpu_flags_avx2', '?')}, AVX-512F: {meta.get('cpu_flags_avx512f', '?')}"],
        ["memory", meta.get("mem_total", "?")],
        ["kernel", meta.get("kernel", "?")],
        ["date (UTC)", meta.get("date", "?")],
    ]))
    w("")
    w("The machine is a shared virtual machine with **2 cores**, and other people were building "
      "and testing on them during the run. Load averages (1, 5, 15 min) at the start of each "
      "section:")
    w("")
    loads = [(k[5:], v) for k, v in meta.items() if k.startswith("load_")]
    w(table(["section", "load average"], [[k, f"`{v}`"] for k, v in loads]))
    w("")
    w("A load above 2 means runnable work from others was queued on our cores: absolute figures "
      "(fps, rays/s) are pessimistic by an unknown factor and vary by tens of percent from run "
      "to run. Ratios measured side by side in one process (section 1) and the scaling "
      "section, where every client is capped to a fixed CPU share, are the more robust figures.")
    w("")

    # 1 -----------------------------------------------------------------------------------------
    w("## 1. Distance to the limit: a client against raw Embree")
    w("")
    w("`igi-bench --scene S --threads T --frames %s --segments %s --width 640 --height 480` "
      "(section 1 of the script) measures, in one process, on the same scene and the same "
      "threads: random shadow segments through `rtcOccluded1` and through 8- and 16-wide "
      "packets (`rtcOccluded8`, `rtcOccluded16`), and the client's tile renderer rendering whole frames at the paper's "
      "settings (3 x 3 interleaving, 4 direct + 18 indirect shadow rays per pixel, 500 caustic "
      "photons per set; the defaults of `RenderSettings`), every ray counted. The two take "
      "turns, in %s rounds of a share of the segments and one frame each, after a warm-up of "
      "each (a pass over the segments, one frame); every figure sums its rounds, so a load that "
      "comes or goes during the run weighs on both sides. The client holds its tiles as in a "
      "session, a few at a time (`--tiles-in-flight`, by default the master's smallest queue "
      "depth, 2 + threads / 8), handing out the next as one is done."
      % (meta.get("bench_frames", "?"), meta.get("bench_segments", "?"), meta.get("bench_frames", "?")))
    w("")
    w("Each row is the median of %s runs (each figure separately; the ratios are medians of "
      "the ratios within each run); the range of "
      "*all / occluded1* over the runs shows how much the machine's load moved it."
      % meta.get("bench_repeats", "?"))
    w("")
    rows = []
    for b in bench:
        r1 = b["embree_occluded1_rays_per_second"]
        r8 = b["embree_occluded8_rays_per_second"]
        lo, hi = b["ratio_all_range"]
        rows.append([
            SCENE_LABELS.get(b["name"], b["name"]), b["triangles"], b["threads"],
            fmt(r1 / 1e6, 1), fmt(r8 / 1e6, 1), fmt(b["embree_occluded16_rays_per_second"] / 1e6, 1),
            fmt(b["client_rays_per_second"] / 1e6, 1), fmt(b["client_shadow_rays_per_second"] / 1e6, 1),
            fmt(b["ratio_all"], 2) + (f" ({fmt(lo, 2)}-{fmt(hi, 2)})" if b["repeats"] > 1 else ""),
            fmt(b["ratio_shadow"], 2), fmt(b["ratio_shadow_16"], 2), fmt(b["ratio_shadow_8_cpu"], 2),
            fmt(b["ratio_16_8"], 2), fmt(b["segments_blocked"] * 100, 0) + " %",
        ])
    w(table(["scene", "triangles", "threads", "rtcOccluded1 Mrays/s", "rtcOccluded8 Mrays/s",
             "rtcOccluded16 Mrays/s", "client, all rays Mrays/s", "client, shadow rays Mrays/s",
             "all / occluded1 (range)", "shadow / occluded1", "shadow / occluded16 (CPU s)",
             "shadow / occluded8 (CPU s)", "occluded16 / occluded8 (CPU s)", "raw segments blocked"],
            rows))
    w("")
    w("How to read it: the raw measurement traces segments between two random points on the "
      "scene's surfaces (area-weighted; the same kind of ray as a shadow ray to a VPL), one "
      "`rtcOccluded1` call each, or 8 (16) consecutive ones per `rtcOccluded8` (`rtcOccluded16`) packet. *All rays* "
      "counts every ray the client traces (eye rays and specular continuations with closest "
      "hit, light paths for the VPLs and caustic photons, shadow rays); *shadow rays* only the "
      "occlusion rays, most of them. The ratio *all / occluded1* is igi-bench's "
      "`client_rays_over_embree_occluded1`: how many rays per second the client gets through, "
      "shading, sampling, building VPL sets and filling tiles included, against bare "
      "single-ray Embree on the same threads. It can exceed 1: the client's rays are not "
      "random segments (eye rays are coherent, shadow rays end at VPLs and light samples rather "
      "than at random surface points), so they can be cheaper than the raw ones.")
    one = [b for b in bench if b["threads"] == 1 and b["name"] not in MANY_LIGHTS]
    many = [b for b in bench if b["threads"] == 1 and b["name"] in MANY_LIGHTS_FIRST]
    many_accumulated = [b for b in bench
                        if b["threads"] == 1 and b["name"] in MANY_LIGHTS_ACCUMULATED]
    if one:
        ratios = [b["ratio_all"] for b in one]
        packets = [b["ratio_packets"] for b in bench]
        w("")
        shadow = [b["ratio_shadow"] for b in one]
        shadow16 = [b["ratio_shadow_16"] for b in one]
        shadow8 = [b["ratio_shadow_8_cpu"] for b in one]
        wide = [b["ratio_16_8"] for b in one]
        width = bench[0].get("client_packet_width", 8)
        verdict = ("above the single-ray limit" if min(shadow) >= 1.05 else
                   "about the single-ray limit" if min(shadow) >= 0.9 else
                   "below the single-ray limit")
        w(f"On the Cornell boxes, on one thread (the per-core figure, least disturbed by the machine's other users), the "
          f"client's shadow rays run at {fmt(min(shadow), 2)} to {fmt(max(shadow), 2)} times the "
          f"raw single-ray rate ({verdict}); per CPU second, at {fmt(min(shadow16), 2)} to "
          f"{fmt(max(shadow16), 2)} times raw 16-wide packets (`rtcOccluded16`) and "
          f"{fmt(min(shadow8), 2)} to {fmt(max(shadow8), 2)} times raw 8-wide ones; all its rays "
          f"at {fmt(min(ratios), 2)} to {fmt(max(ratios), 2)} times the single-ray rate. Raw "
          f"16-wide packets run {fmt(min(wide), 2)} to {fmt(max(wide), 2)} times 8-wide ones "
          f"here. The client traces {width}-wide packets (TraceableScene::packetWidth: 16 where "
          f"the CPU has AVX-512 and Embree native 16-wide packets, else 8): each chunk of 8 x 8 "
          f"pixels queues the shadow rays of all its points (light samples and VPLs), sorts them "
          f"by target and traces them in packets, then sums each point's in the order queued, so "
          f"the images do not depend on the packet width; eye rays go in packets too, as do "
          f"the rays that leave the first hits along mirror and glass. The "
          f"client's figure includes its shading, sampling, VPL and photon building and tile "
          f"filling, which the raw figure does not. The rows with {meta.get('nproc', 2)} "
          f"threads compete with everyone else on the 2 cores and scatter more.")
    if many:
        w("")
        w("**The many-light interiors** (issue 36's target: the client's shadow rays at 0.9 times "
          "raw `rtcOccluded16` per CPU second or more), one thread, first frames after a change "
          "(igi-bench's frames, 1 + 5 shadow rays per point to lights and VPLs there, "
          "`render.first_frame_divisor`): " +
          "; ".join(f"{SCENE_LABELS.get(b['name'], b['name']).split(' (')[0]} "
                    f"{fmt(b['ratio_shadow_16'], 2)}" for b in many) +
          ("; accumulated frames (`igi-bench --accumulated`, 4 + 18): " +
           "; ".join(f"{SCENE_LABELS.get(b['name'], b['name']).split(',')[0]} "
                     f"{fmt(b['ratio_shadow_16'], 2)}" for b in many_accumulated)
           if many_accumulated else "") +
          ". Here a shadow ray costs the client more than it costs Embree: each point chooses "
          "its light samples in the light tree and its VPLs from the pool by importance, and "
          "a glossy point evaluates its lobe and the VPL's for every connection and continues "
          "its path with single rays. A first frame traces a quarter of the shadow rays of an "
          "accumulated one for the same eye rays, light paths and choice among the pool's VPLs, "
          "so its rays carry more of that work each: it is faster, but further from raw "
          "Embree per ray.")
    w("")
    # Changes to the client's non-ray work, each measured side by side against the build
    # before it (scripts/bench_side_by_side.sh, scripts/bit_identical.sh): written by hand in
    # the document, kept here as they are.
    w("<!-- BEGIN GENERATED non-ray-work -->")
    w(generated_block(doc, "non-ray-work") or "Nothing measured by hand yet.")
    w("<!-- END GENERATED non-ray-work -->")
    w("")

    # 2 -----------------------------------------------------------------------------------------
    w("## 2. End-to-end frame rate at 640 x 480, paper settings")
    w("")
    w("`igi-master --scene S --local-clients C --frames %s --width 640 --height 480 "
      "--interleave 3x3 --direct-samples 4 --indirect-vpls 18 --caustic-photons 500 "
      "--stats-json F` for C = 1 and 2 (section 2 of the script). With C local clients each "
      "gets nproc / C render threads; the master (all cores) runs beside them on the same "
      "2 cores. fps counts from the moment every client is ready (scene loaded, BVH built) "
      "to the last frame composited, with accumulation on (the default)." % meta.get("fps_frames", "?"))
    w("")
    w(table(FPS_HEADER, fps_rows(fps)))
    w("")
    w("**How the frame time is split** (all from `--stats-json`): *ms / frame* is the wall time "
      "of the run over its frames (1 / fps; up to two frames are in flight, so a frame's own "
      "latency, `frames[].seconds`, is longer). *Client render* is a client's threads' busy time "
      "(`clients[].busy_seconds`: the render time its tiles report, over its threads) per "
      "frame, averaged over clients; *client waiting* is the rest of the time it was connected "
      "(`idle_seconds`): waiting for tile assignments and for its results to leave, i.e. the "
      "network and the master's dispatch latency. Client render + client waiting = ms / frame. "
      "*Master decode* (`frames[].decode_seconds`: zstd and the copy of a tile's still quantized "
      "codes into the frame, summed over the master's threads) and *master composite* "
      "(`composite_seconds`: dequantization, discontinuity buffer and accumulation) are master CPU time per frame; they overlap with the clients' work "
      "(the master decodes tiles as they come and composites a frame while the next one "
      "renders), so they add to the wall time only through the cores they take from the clients "
      "on this 2-core machine. On loopback the network itself is a memory copy; the waiting "
      "column includes the end of the run (no tiles left) and scheduling delays on the shared "
      "cores.")
    w("")
    best = max((s for s in fps if s["name"] == "cornell-default"), key=lambda s: s["fps"], default=None)
    if best:
        w(f"Paper, for comparison: the Cornell-like room with a glass ball at these settings ran at "
          f"{PAPER_CORNELL_FPS} fps on 8 clients (AthlonMP 1800+, about 0.5 M rays/s each, i.e. "
          f"about 4 M rays/s together). Here the whole 2-core machine, shared with the master and "
          f"other users, reaches {fmt(best['fps'], 2)} fps on the default scene "
          f"({fmt(best['rays_per_second'] / 1e6, 1)} M rays/s, "
          f"{fmt(best['rays_per_second'] / PAPER_RAYS_PER_CLIENT, 0)} times one of the paper's "
          f"clients).")
        w("")

    if fullhd:
        size = f"{meta.get('fullhd_width', '?')} x {meta.get('fullhd_height', '?')}"
        w(f"### Full HD: {size}" if size == "1920 x 1080" else
          f"### The full-HD rows at {size} (a --quick run)")
        w("")
        w(f"The same command at `--width {meta.get('fullhd_width', '?')} --height "
          f"{meta.get('fullhd_height', '?')}`, on the default scene and on the glossy interior lit "
          f"by 96 small lights (frames: {meta.get('fullhd_frames', '?')}), 1 and 2 local clients. "
          "fps here includes the first frame's pipeline fill, which weighs more with fewer "
          "frames. The scaling over clients (section 3) is not run at this size: a client capped "
          "at a sixteenth of a core would take minutes per frame.")
        w("")
        w(table(FPS_HEADER, fps_rows(fullhd)))
        w("")
        by_name = {}
        for s in fullhd:
            by_name.setdefault(s["name"], []).append(s)
        for name, runs in by_name.items():
            small = [f for f in fps if f["name"] == name]
            best_hd = max(runs, key=lambda r: r["fps"])
            if small:
                best_small = max(small, key=lambda r: r["fps"])
                ratio = (best_hd["fps"] * best_hd["width"] * best_hd["height"]) / (
                    best_small["fps"] * best_small["width"] * best_small["height"])
                w(f"- {SCENE_LABELS.get(name, name)}: {fmt(best_hd['fps'], 2)} fps at full HD "
                  f"against {fmt(best_small['fps'], 2)} at 640 x 480: {fmt(ratio, 2)} times the "
                  f"pixels per second (1: the cost per pixel does not depend on the size).")
            else:
                w(f"- {SCENE_LABELS.get(name, name)}: {fmt(best_hd['fps'], 2)} fps at full HD "
                  f"({fmt(best_hd['pixels_per_second'] / 1e6, 2)} M pixels/s).")
        w("")

    # 3 -----------------------------------------------------------------------------------------
    w("## 3. Scaling over clients")
    w("")
    capped = meta.get("scale_capped") == "1"
    sh = share(meta)
    if capped:
        w("Each client is a separate `igi-client --threads 1` process connecting over loopback "
          "(`igi-master --clients N --listen 127.0.0.1:0 --secret-file F`, authenticated with a "
          "random secret), started in its own cgroup (v1 `cpu` controller, "
          f"`cpu.cfs_period_us` = {meta.get('scale_period_us')}, `cpu.cfs_quota_us` = "
          f"{meta.get('scale_quota_us')}, `cpu.shares` = {meta.get('scale_shares', 1024)}): every "
          f"client gets at most **{100 * sh:.2f} % of one core**, 16 clients together "
          f"{16 * sh:.2f} cores; the high `cpu.shares` makes the share a guarantee as well when "
          "others load the machine, while the quota keeps it a cap. The other core is left to the "
          "master (uncapped) and to the machine's other users. With a fixed share per client "
          "the ideal is linear in N, as with the paper's one-machine-per-client cluster "
          f"(Table 1). Default scene, {meta.get('scale_width')} x {meta.get('scale_height')}, "
          "paper settings; the number of frames grows with N so that every run takes about as "
          "long. "
          "Section 3 of the script.")
    else:
        w("**Cgroups were not writable during this run: the clients ran uncapped on 2 shared "
          "cores, so this section shows the machine saturating, not the system's scaling.**")
    w("")
    rows = []
    for s in scaling:
        cg = s["cgroups"]
        rows.append([
            s["n"], s["frames"], fmt(s["fps"], 3), fmt(s["steady_fps"], 3), fmt(s["speedup"], 2),
            fmt(100 * s["efficiency"], 0) + " %" if s["efficiency"] is not None else "n/a",
            fmt(s["rays_per_second_per_client"] / 1e6, 2),
            fmt(100 * s["share_used"], 0) + " %" if s["share_used"] is not None else "n/a",
            fmt(s["distinct_sets_per_client_frame"], 1), s["duplicate_tiles"],
            fmt(s["master_decode_ms"] + s["master_composite_ms"], 0),
            (fmt(100 * cg["throttled_share"], 0) + " %") if cg and cg["throttled_share"] is not None else "n/a",
        ])
    w(table(["clients N", "frames", "fps (whole run)", "fps (steady)", "speed-up", "efficiency",
             "M rays/s per client", "share used", "distinct k / client / frame",
             "duplicate tiles", "master CPU ms / frame", "CFS periods throttled"], rows))
    w("")
    if plot:
        w(f"![fps and parallel efficiency against the number of clients]({rel_perf}/scaling.png)")
        w("")
    w("*fps (whole run)* counts from all clients ready to the last frame; *fps (steady)* from "
      "frame 1 shown to the last (the times of the master's per-frame log lines), which "
      "leaves out the pipeline fill of the first frame. *Speed-up* and *efficiency* "
      "(fps(N) / (N fps(1))) use the steady rate. *Share used*: a client's rays per second "
      "over (its CPU share x the rays per second of one uncapped client thread on this scene, "
      "section 1): how much of its cap a client turned into rays (the two were measured at "
      "different moments of a noisy machine, so 10 % either way means nothing). *Duplicate "
      "tiles*: tiles handed to a second client because the first was late (after 50 ms) near "
      "the end of a frame, and dropped when both came back: work wasted to cut a frame's tail "
      "(a dropped copy's rays are not counted). "
      "*CFS periods throttled* is "
      "`nr_throttled / nr_periods` summed over the clients' cgroups (`cpu.stat`): close to "
      "100 % means the cap, not a lack of work, bounded every client, i.e. the share was really "
      "enforced. *Distinct k*: with more clients each one gets more different interleaving sets "
      "per frame and must build each set's VPLs and caustic photons (the paper reports about 2 "
      "on average); this per-set preprocessing is the part of the work that does not shrink "
      "with N.")
    w("")
    one_client = next((s for s in scaling if s["n"] == 1), None)
    ref = one_client["share_used"] if one_client and one_client["share_used"] else None
    weak = [s for s in scaling if ref and s["share_used"] is not None and s["share_used"] < 0.8 * ref]
    if weak and capped:
        w("Where *share used* falls well below its value for one client (" +
          ", ".join(f"N = {s['n']}: {fmt(100 * s['share_used'], 0)} %" for s in weak) +
          f", against {fmt(100 * ref, 0)} % for N = 1), each client turned less of its cap into "
          "rays. The clients together then take up to "
          f"{max(s['n'] for s in weak)} x {100 * sh:.2f} % = "
          f"{max(s['n'] for s in weak) * sh:.2f} core; the master and the machine's other users "
          "(load averages above) compete for the rest and for memory bandwidth and caches, and "
          "the CPU time charged to a client includes kernel networking and scheduling, which "
          "grow with the number of processes. The loss at that N is the machine's as much as "
          "the renderer's: the master is far from its ceiling (section 4) and duplicate tiles "
          "(column above) are few against the tiles of the run.")
        w("")
    strong = [s for s in scaling if ref and s["share_used"] is not None and s["share_used"] > 1.1 * ref]
    if strong and capped:
        w("Efficiencies above 100 % come from the baseline: one capped client turned only "
          f"{fmt(100 * ref, 0)} % of its share into rays, several turned up to "
          f"{fmt(100 * max(s['share_used'] for s in strong), 0)} %. With a quota (here "
          f"{100 * sh:.2f} % of a core) smaller than the kernel's bandwidth slice (5 ms by "
          "default), CFS likely hands a lone cgroup's runtime out in pieces that its render and network "
          "threads, on different cores, cannot always use; the figure to read is the fps growing "
          "with N while every client stays capped, not the exact percentage. Before the master "
          "kept four frames open (it kept two), 16 such clients reached only about 60-70 % "
          "efficiency, idle in the tail of every frame.")
        w("")
    if scaling and capped:
        top = max(scaling, key=lambda s: s["rate"])
        top_mpx = top["rate"] * top["width"] * top["height"] / 1e6
        ceil_mpx = max((c["mpx_per_second"] or 0 for c in ceiling), default=0)
        w(f"Paper: near-linear from 1 to 16 clients (Table 1), until the server's ceiling of about "
          f"{PAPER_CEILING_MPX} M pixels/s. One capped client here traces about "
          f"{fmt(scaling[0]['rays_per_second_per_client'] / 1e6, 2)} M rays/s (one of the "
          f"paper's AthlonMP clients: about {PAPER_RAYS_PER_CLIENT / 1e6} M rays/s), so the "
          f"experiment has the paper's scale. The highest rate reached, "
          f"{fmt(top['rate'], 2)} fps with {top['n']} clients, is {fmt(top_mpx, 2)} M pixels/s, "
          + (f"{fmt(ceil_mpx / top_mpx, 0)} times below the master's ceiling measured in "
             f"section 4 ({fmt(ceil_mpx, 1)} M pixels/s)." if ceil_mpx and top_mpx else
             "(no ceiling measured to compare with)."))
        w("")

    # 4 -----------------------------------------------------------------------------------------
    w("## 4. The master's ceiling")
    w("")
    w("`igi-master --scene scenes/cornell/cornell.json --local-clients 2 --client-threads 1 "
      "--replay-clients --threads T --frames F --width W --height H` plus the paper settings "
      "(section 4 of the script). Replaying clients render each tile once and afterwards resend "
      "that result whenever the tile is asked for, so the master's work (receiving, zstd "
      "decompression, dequantization, scatter, discontinuity filter, accumulation, scheduling) "
      "is the bottleneck. The first %d frames are left out: a replaying client renders a "
      "tile for real the first time it is asked for it, and two frames are in flight, so the "
      "first two or three frames are rendered. The ceiling is the frames from frame %d shown to "
      "the last, over the time between their lines in the master's log. The replaying clients "
      "(1 thread each) share the 2 cores with the master, so T = 2 is not two free cores."
      % (CEILING_SKIP, CEILING_SKIP))
    w("")
    rows = []
    for c in ceiling:
        r = c["run"]
        mpx = c["mpx_per_second"]
        rows.append([
            c["threads"], f"{c['width']} x {c['height']}", r["frames"],
            fmt(mpx, 2), fmt(mpx * 1e6 / (c["width"] * c["height"]), 1) if mpx else "n/a",
            fmt(c["mpx_per_second_whole_run"], 2),
            fmt(r["master_decode_ns_per_pixel"], 0),
            fmt(r["master_composite_ms"], 1),
            fmt(mpx / PAPER_CEILING_MPX, 1) if mpx else "n/a",
        ])
    w(table(["master threads", "image", "frames", "M pixels/s (steady)", "fps (steady)",
             "M pixels/s (whole run)", "decode ns / pixel (CPU, summed over threads)",
             "composite ms / frame", "x paper's 1.5 M px/s"], rows))
    w("")
    w("*Whole run* includes start-up and the really rendered first frames, for reference. "
      "Decode and composite come from `--stats-json` (whole run).")
    w("")
    pairs = []
    for res in sorted({(c["width"], c["height"]) for c in ceiling}):
        by = {c["threads"]: c["mpx_per_second"] for c in ceiling if (c["width"], c["height"]) == res}
        if by.get(1) and by.get(2):
            pairs.append(f"{fmt(by[2] / by[1], 2)} at {res[0]} x {res[1]}")
    if pairs:
        w("Two master threads against one: " + ", ".join(pairs) + ". On this machine the "
          "second thread shares the second core with the two replaying clients and with other "
          "users, so this is not the master's own scaling; on a free machine with more cores "
          "the decode (per tile, on the pool) and the filter would spread over the threads.")
        w("")
    if stages:
        w("**The same work by stage, without clients or network**: `igi-composite-bench --width W "
          "--height H --frames F --rounds 3` decodes the tiles of a synthetic frame shaped like "
          "the default scene's (walls, a sphere, 3 x 3 interleaved noisy irradiance, a mirror's "
          "unfiltered radiance), scatters them, and filters, accumulates and averages, all on one "
          "thread, with accumulation and the progressive filter on; the fastest of three rounds. "
          "Nothing else runs in its process, so this is the master's own per-pixel cost; the "
          "replay ceiling above adds receiving, scheduling and the clients sharing the cores.")
        w("")
        names = list(stages[0]["ns"].keys())
        w(table(["image"] + [f"{n} (ns / pixel)" for n in names] + ["M pixels/s on one thread"],
                [[f"{st['width']} x {st['height']}"] + [fmt(st["ns"].get(n), 1) for n in names]
                 + [fmt(st["mpx"], 1)] for st in stages]))
        w("")
    w(f"Paper: the server topped out near {PAPER_CEILING_MPX} M pixels/s, about 5 fps at "
      "640 x 480.")
    w("")

    # 5 -----------------------------------------------------------------------------------------
    w("## 5. Bytes on the wire")
    w("")
    w("Per pixel, each plane is quantized before zstd (level -1: literals stored raw, which zstd decodes faster for a few more bytes; protocol/ChannelCodec.h gives the measurement) compresses the tile "
      "(docs/PROTOCOL.md, \"Channels\"); as 32-bit floats a pixel of all six planes would be "
      "16 floats = 64 bytes:")
    w("")
    w(table(["plane", "as floats", "quantized (before zstd)"], [
        ["irradiance (RGB)", 12, "4 (shared-exponent RGB)"],
        ["reflectance (RGB)", 12, "3 (sRGB u8)"],
        ["normal", 12, "2 (octahedral u8 x 2)"],
        ["depth", 4, "2 (log u16)"],
        ["unfiltered (RGB, mirrors/glass/caustics)", 12, "4 (shared-exponent RGB); left out when zero in the whole tile"],
        ["glossy (RGB, the Phong lobe's radiance)", 12, "4 (shared-exponent RGB); left out when zero in the whole tile (every tile of a scene without glossy materials)"],
        ["**all six**", "**64**", "**19**"],
    ]))
    w("")
    if codec:
        w("`igi-codec-bench --rounds %s` (section 5 of the script), on its synthetic typical "
          "32 x 32 tile with the five planes of a diffuse scene (modelled on the default scene's "
          "tiles, which have no glossy plane):"
          % ("5" if not quick else "2"))
        w("")
        w("```")
        w(codec["text"])
        w("```")
        w("")
        if "wire" in codec:
            w(f"So {codec['floats']} bytes/pixel as floats, {codec['quantized']} quantized, "
              f"{fmt(codec['wire'], 2)} on the wire after zstd: "
              f"{fmt(codec['floats'] / codec['wire'], 1)} x smaller than floats, "
              f"{fmt(codec['quantized'] / codec['wire'], 1)} x from zstd alone. One core decodes "
              f"{fmt(codec.get('decode_mpx'), 1)} M pixels/s, of which zstd is "
              f"{fmt(codec.get('zstd_ns'), 0)} of {fmt(codec.get('decode_ns'), 0)} ns/pixel.")
            w("")
        if "planes" in codec:
            w("Per plane, on the same tiles, each plane compressed alone (zstd sees only that "
              "plane; together they compress a little better, to the figure above):")
            w("")
            w(table(["plane", "quantized B / px", "after zstd B / px", "ratio"], [
                [name, p["quantized"], fmt(p["compressed"], 2),
                 fmt(p["quantized"] / p["compressed"], 1) if p["compressed"] else "-"]
                for name, p in codec["planes"].items()]))
            w("")
            w("Irradiance, the noisy plane, is most of the wire; reflectance and normals are "
              "piecewise constant on these surfaces and nearly vanish.")
            w("")
    w("End to end, from the runs of section 2 (`frames[].wire_bytes`: every tile result "
      "received, 24-byte headers and duplicates included, over the pixels):")
    w("")
    rows = []
    for s in fps:
        if s["clients"] != 1:
            continue
        bpp = s["wire_bytes_per_pixel"]
        frame_bytes = bpp * s["width"] * s["height"]
        rows.append([
            SCENE_LABELS.get(s["name"], s["name"]), fmt(bpp, 2), fmt(frame_bytes / 1e6, 2),
            fmt(s["wire_bytes_per_second"] / 1e6, 2),
            fmt(125e6 / frame_bytes, 0), fmt(12.5e6 / frame_bytes, 0),
        ])
    w(table(["scene", "wire B / px", "MB / frame (640 x 480)", "MB/s in the run",
             "fps a Gigabit uplink could carry", "fps one 100 Mbit client link could carry"], rows))
    w("")
    ceil_fps = max((c["mpx_per_second"] * 1e6 / (c["width"] * c["height"])
                    for c in ceiling if c["mpx_per_second"] and c["width"] == 640), default=None)
    w("The paper's network had 100 Mbit/s per client and one Gigabit uplink to the master. "
      "A client's link carries a frame's share of bytes, not the whole frame: with N clients "
      "each sends 1/N of it, so the last column is the rate that one client alone could feed."
      + (f" For comparison, the master composites at most about {fmt(ceil_fps, 0)} fps at "
         f"640 x 480 here (section 4)." if ceil_fps else ""))
    w("")

    # Section 6 comes from its own script; its block is carried over from the current document.
    w("## 6. Many lights: light samples and VPLs by power or by importance")
    w("")
    w("`scripts/bench_many_lights.sh` (its own script: about an hour the first time, for the "
      "references) renders scenes lit by many small lights with IGI and with our path tracer and "
      "compares each image with a path-traced reference: the interior lit by 96 small ceiling "
      "lights (`scenes/interior/diffuse.json`, `glossy.json`; `sculptures.json` adds 133,000 "
      "triangles of ceramic pieces) and the Sponza atrium with the Stanford bunny, 210,496 "
      "triangles lit by 120 small lights under its arcades on three floors "
      "(`scenes/sponza/arcades.json`, written by `scripts/make_sponza_scene.py`; its meshes come "
      "from `../shared/scenes`). Variants: `igi-power` is the paper's IGI (light samples by "
      "power, `--light-sampling power`, and every point connected to every VPL of its set, "
      "`--vpl-sampling all`); `igi-tree` takes its light samples from the light tree "
      "(client/lights/LightTree.h); `igi-importance` also chooses each point's VPLs by importance "
      "(`--vpl-sampling importance`, client/lights/VplChoice.h: each set's light paths leave a pool of "
      "8 x 18 VPLs and each point connects to 18 of them, drawn by what each can give it), what "
      "`auto` picks from 8 emitters on. The path tracer takes one light sample per vertex by "
      "power or by the tree.")
    w("")
    w("<!-- BEGIN GENERATED many-lights -->")
    w(generated_block(doc, "many-lights") or "Not measured yet: run scripts/bench_many_lights.sh.")
    w("<!-- END GENERATED many-lights -->")
    w("")
    w("How to read it (from the run above). The light tree (Estevez and Kulla 2018, with "
      "pbrt-v4's bounds) weighs each light, or group of lights, by power x the best emitting "
      "cosine toward the point x the best receiving cosine at it / squared distance and walks "
      "down by those weights; the VPL choice weighs each VPL of the pool by its brightness x "
      "both cosines / the clamped squared distance, mixed with a tenth of a uniform choice among "
      "the VPLs that can reach the point, and draws 18 by systematic sampling, each weighted "
      "count / (18 p). Both are unbiased (a weight is zero only where the light cannot reach the "
      "point's front side) and are functions of the point, the set and the frame, so the image "
      "does not depend on which client rendered what (tests/EndToEnd: three clients render a "
      "many-light scene bit for bit as one does). In the Sponza atrium, where most lights are "
      "out of reach of most points (other floors, other side, behind pillars), IGI with both "
      "reaches the paper's error (power, every VPL, 16 frames) 3.9 times sooner, and has 3.6 "
      "times less error at its time; one frame's speckle (pixels more than 4x the reference) "
      "falls from 0.21 % to 0.04 %, and the first frame's bias from -32 % to -3 %. The light "
      "tree alone gives 2x. In the "
      "single-room interiors every light reaches most of the room, so the choice has less to "
      "gain: a frame costs 1.2-1.5 times the tree's (the weights of a pool of about 170 VPLs "
      "per point, and connections that no longer share their VPL with the neighbours'), for "
      "1.2-1.7 times less error per frame: at equal time power's error over its own is 0.92 on "
      "the diffuse room (8 % more error than power) and 1.18 on the glossy one, and one frame's "
      "speckle is half power's in both. `auto` uses the choice from 8 emitters on all the "
      "same: it never lost more than 8 % at equal time here and gains several times where lights are many and far apart, "
      "and the speckle of the first frames after a change is what a user sees. For the path "
      "tracer, which takes one light sample per vertex, the tree is worth 3 to 13 times less "
      "error at equal time.")
    w("")
    w("### Shadow rays per pixel where IGI chooses them by importance")
    w("")
    w("Issue 36 asks whether the paper's 4 direct + 18 indirect shadow rays per pixel, chosen "
      "for a room with one light, should stay where the light tree and the VPL choice pick each "
      "ray by what it can give. `scripts/shadow_rays_report.py` (its own script, about 10 minutes "
      "once the references are cached; `--render-references` renders those it lacks, 5 to 15 "
      "minutes each) renders the many-light scenes with other pairs at the same seeds and "
      "compares the error each buys in the same time.")
    w("")
    w("<!-- BEGIN GENERATED shadow-rays -->")
    w(generated_block(doc, "shadow-rays") or "Not measured yet: run scripts/shadow_rays_report.py.")
    w("<!-- END GENERATED shadow-rays -->")
    w("")
    w("How to read it. Halving the rays (2 + 9) makes a frame 1.4 to 1.8 times faster here, not "
      "2: at 160 x 120 with one client the light paths, the light-tree walks and the master's "
      "work weigh more than at 640 x 480. At equal frames its error is 1.15 to 1.53 times "
      "4 + 18's in the rooms and 1.35 to 2.52 times in the arcades, and the ratio grows as "
      "frames accumulate (more after 64 frames than after 4, for every pair, 2 + 18 included), "
      "so part of the difference does not average away; why is not measured. In the two "
      "interiors, where 2 + 9 was first picked (by a one-seed sweep of 16 pairs by hand), it "
      "gives 0.65 to 0.99 times the error in the same time; in the sculptures room, held out, "
      "0.75 to 0.92; in the Sponza arcades, held out, 0.97 after one frame and, from 4 frames "
      "on, 1.18 to 1.90 times more error in the same time, whichever of the three pairs. So the "
      "paper's 4 + 18 stays the default: a smaller pair wins in single rooms and loses where the "
      "lights are many and far apart, which is where the importance choice matters most. "
      "Counted in shadow rays instead of seconds (what a larger image or cheaper non-ray work "
      "would approach), 2 + 9 gains more in the rooms (0.58 to 0.78) and the three smaller "
      "pairs still lose in the arcades after 64 frames (1.21 to 1.29).")
    w("")
    w("### The first frame after a change")
    w("")
    w("Issue 36 asks for the first frame after a change faster than on the day it was filed, "
      "at equal or lower error. The first frame now has the light paths and the bound of the "
      "frames accumulated after it: Russian roulette past the paper's walk (which stops after 4 "
      "vertices), and, with the compensation, the bound twice as far "
      "(`LightingSetBuilder::kCompensatedClampScale`). What restores the bound's cut begins with "
      "the second frame, in the running mean: the Lambertian points' compensation rays, the VPLs' "
      "photons and the pooled caustics, and the second points that a glossy point's continuation "
      "ray shades where it lands (`LightingSet::compensationRays`; the ray itself still finds "
      "the lights the lobe sees). That second shading, with every light sample and VPL again, "
      "took about half of the glossy room's first frame (by hand, with a throwaway build that "
      "switched it off: igi-bench's CPU time for 3 first frames at 320 x 240, 1.60 s against "
      "0.83 s). Where the points choose their VPLs by importance (from 8 emitters on: the rooms "
      "and the arcades, not the boxes), the first frame also takes a quarter of the light "
      "samples and VPLs per point, 1 + 5 of 4 + 18, chosen from the accumulated frames' pool "
      "of 144 (`render.first_frame_divisor`, `--first-frame-divisor`; auto: 4 there, 1 "
      "elsewhere); the frames after it keep 4 + 18. That quarter was chosen on the diffuse "
      "room and the arcades with `scripts/first_frame_pairs.py` (first frames at 160 x 120, "
      "medians of 8 seeds; the client's render seconds for 3 frames at 320 x 240, two rounds; "
      "its run of 2026-11-29 16:10 UTC, whose figures are in `kAutoFirstFrameDivisor`'s "
      "comment): 1 + 5 took 0.48-0.57 and 0.57-0.63 of 4 + 18's time for 1.29 and 1.25 times "
      "its relMSE; 2 + 6 took 0.62-0.64 and 0.62-0.70 for 1.13 and 1.15; dividing the pool as "
      "well cost much more error for no less time (2 + 6 from 48 VPLs: 0.46-0.65 of the time "
      "for 1.41 and 1.78 times the relMSE). The sculptures and glossy rooms were measured after "
      "the choice. `scripts/first_frame_report.py "
      "--baseline-bin DIR` (its own script, about 15 minutes once the references are cached) "
      "renders each scene's first frames with a baseline build and with this one, at the same "
      "seeds, and times the client on each in turns. The baseline below is 37e04fa, the build "
      "of 2026-11-27 on which issue 36 was filed.")
    w("")
    w("<!-- BEGIN GENERATED first-frame -->")
    w(generated_block(doc, "first-frame") or "Not measured yet: run scripts/first_frame_report.py.")
    w("<!-- END GENERATED first-frame -->")
    w("")
    w("How to read it (from the run above). In the three rooms, where the first frame takes a "
      "quarter of the light samples and VPLs per point, it is 2.0 to 3.3 times as fast as on the "
      "day of the issue (0.49, 0.48 and 0.30 times its CPU time: the diffuse room, the "
      "sculptures, the glossy room) with 0.13 to 0.29 times its relMSE, which meets issue 36's "
      "1.8 times faster at equal or lower error there. Most of the error gain came before (the "
      "light paths and bound of the accumulated frames; this report's run against e3b013e "
      "measured that build's first frames in the rooms at 0.027 to 0.054, where that day's are "
      "0.19 to 0.22), and the quarter spends part of it on time: the rooms' first frames have "
      "1.3 to 1.4 times the relMSE of 4 + 18's on this build (the previous run of this report: "
      "0.0219, 0.0224 and 0.0405). The glossy room's also no longer shades a second point at its "
      "glossy points, which leaves it 8 % too dark (medians of the mean relative bias; 12 % that "
      "day). The Sponza arcades, held out, had as much error in their first frame as on that "
      "day, with no margin to spend: 2.1 times as fast, at 1.23 times that day's relMSE and "
      "twice its speckle (0.11 % of the pixels against 0.06 %); after 4 and 16 frames 1.05 and "
      "1.02 times that day's error (at equal frames: this report does not time accumulated "
      "ones). So the target is met in the rooms and "
      "missed in the arcades, where `--first-frame-divisor 1` keeps the first frame at 4 + 18 "
      "(0.87 times that day's time at 0.98 times its error, the previous run). The Cornell boxes "
      "choose no VPLs by importance and keep their first frame: 0.76 to 1.05 times that day's "
      "CPU time (the same code as in the previous run, 0.78 to 1.03: the machine's noise) at "
      "0.42 to 0.98 times its error. What the first frame has besides the divisor was chosen on six "
      "scenes (default, spot, cornell-glossy and the three rooms) by hand, with throwaway builds "
      "that switched one part at a time (not kept, so not re-runnable; their figures are in "
      "issue 36's notes); the other four Cornell boxes and the arcades were measured after the "
      "choice. Along the accumulation, after 4 and 16 frames, the error is 0.16 to 1.05 times "
      "that day's on every scene but cornell-glossy, where it is 1.50 and 1.40 times, not for "
      "its first frame (0.98 times that day's error) but for e6db11a, which stopped the "
      "discontinuity buffer averaging the glossy radiance across curved surfaces (a blur of the "
      "reflections that accumulating does not remove, worth more than this noise in long runs): "
      "that change alone, on the build of that day, takes cornell-glossy's relMSE after 16 "
      "frames from 0.0012-0.0013 to 0.0015-0.0019 (seeds 6 to 8, by hand).")
    w("")

    w("## 7. The web view: key to image, and what it costs")
    w("")
    w("`scripts/bench_view.sh` (its own script, about 5 minutes) opens the web view "
      "(`igi-master --view`, docs/VIEW.md) in Debian's Chromium, presses keys in the page and "
      "times each until the first image that shows the move, and compares the frame rate of "
      "runs with a page open against runs without.")
    w("")
    w("<!-- BEGIN GENERATED view -->")
    w(generated_block(doc, "view") or "Not measured yet: run scripts/bench_view.sh.")
    w("<!-- END GENERATED view -->")
    w("")

    w("## 8. Across network links: frame rate against link rate")
    w("")
    w("`scripts/bench_network.sh` (its own script, root, about 6 minutes) runs the master and "
      "each client on its own host, made of a network namespace with its own address and link, "
      "and limits the links with tc (tests/NetworkLab.h makes the same hosts for the LAN tests).")
    w("")
    w("<!-- BEGIN GENERATED network -->")
    w(generated_block(doc, "network") or "Not measured yet: run scripts/bench_network.sh.")
    w("<!-- END GENERATED network -->")
    w("")

    w("## 9. Instances: a mesh placed many times, built once")
    w("")
    w("`scripts/bench_instancing.sh BASE_BIN NEW_BIN` (its own script, about a minute) runs a "
      "master and one client process on Khronos' MetalRoughSpheresNoTextures (98 nodes placing "
      "one sphere, each with its own material) with a build from before instancing, which "
      "flattens the nodes into one mesh of 1,040,409 triangles, and with this one, which builds "
      "the sphere's BVH once and places it by 98 Embree instances (docs/SCENE_FORMAT.md, "
      "\"Instances\"), alternately, and compares the client's peak memory and the scene build "
      "time it reports.")
    w("")
    w("<!-- BEGIN GENERATED instancing -->")
    w(generated_block(doc, "instancing") or "Not measured yet: run scripts/bench_instancing.sh.")
    w("<!-- END GENERATED instancing -->")
    w("")

    w("## What is not measured here")
    w("")
    w("- Real network: sections 1-7 run on loopback on one machine. Section 8 limits link rates "
      "between network namespaces, still on one machine: no real NIC, no latency.")
    w("- Peers other than raw Embree (Cycles, Embree's `pathtracer`): they render a different "
      "thing (converged path tracing) and are not timed by this script.")
    w("- Clients on separate machines: the scaling section emulates them with CPU caps on one "
      "2-core machine; memory bandwidth and caches are still shared.")
    w("")
    return "\n".join(L)


if __name__ == "__main__":
    main()
