#!/usr/bin/env python3
"""Client memory and scene build time, flattened against instanced (docs/PERFORMANCE.md,
"Instances"; issue 36). Runs a master and one client (a process of its own, so that its peak
resident memory is its own) on a scene with two builds, alternately, `--runs` times each: BASE_BIN
(a build from before instancing: every node's copy of a shared mesh flattened into one mesh) and
NEW_BIN. Reports the client's peak resident set (getrusage of the waited client process), the
scene build time the client reports (load, Embree BVHs and the first scene version: the master's
"triangles built in" line), the frame time, and the relMSE between the two builds' images.
Writes docs/perf/instancing.json and the generated block "instancing" of docs/PERFORMANCE.md.
Python 3 standard library only."""

import argparse
import json
import os
import re
import socket
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import report_util  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_SCENE = os.path.join(ROOT, "..", "shared", "scenes", "gltf", "MetalRoughSpheresNoTextures",
                             "glTF", "MetalRoughSpheresNoTextures.gltf")


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def run_once(bin_dir, scene, out_dir, tag, args):
    """One master and one client; returns the client's peak RSS (kB), its build time, the
    frames' mean time and the image's path."""
    port = free_port()
    secret = os.path.join(out_dir, "secret")
    if not os.path.exists(secret):
        with open(secret, "wb") as f:
            f.write(os.urandom(32).hex().encode())
        os.chmod(secret, 0o600)
    exr = os.path.join(out_dir, f"{tag}.exr")
    stats = os.path.join(out_dir, f"{tag}.json")
    log = open(os.path.join(out_dir, f"{tag}.master.log"), "w")
    master = subprocess.Popen(
        [os.path.join(bin_dir, "igi-master"), "--scene", scene, "--allow-outside-paths",
         "--clients", "1", "--listen", f"127.0.0.1:{port}", "--secret-file", secret,
         "--frames", str(args.frames), "--width", str(args.width), "--height", str(args.height),
         "--output", exr, "--stats-json", stats, "--log-level", "info"],
        stdout=log, stderr=subprocess.STDOUT)
    time.sleep(0.3)
    client_log = open(os.path.join(out_dir, f"{tag}.client.log"), "w")
    client = subprocess.Popen(
        [os.path.join(bin_dir, "igi-client"), "--connect", f"127.0.0.1:{port}", "--secret-file",
         secret, "--threads", str(args.threads), "--reconnect-seconds", "0",
         "--connect-timeout", "30"],
        stdout=client_log, stderr=subprocess.STDOUT)
    _, status, usage = os.wait4(client.pid, 0)
    client.returncode = os.waitstatus_to_exitcode(status)
    master.wait()
    log.close()
    client_log.close()
    if master.returncode != 0:
        raise RuntimeError(f"{tag}: the master failed ({master.returncode}); see {log.name}")
    text = open(log.name, errors="replace").read()
    m = re.search(r"is ready: (\d+) triangles built in ([0-9.]+) s", text)
    if not m:
        raise RuntimeError(f"{tag}: no 'triangles built in' line in {log.name}")
    frames = json.load(open(stats))["frames"]
    frame_ms = [1000.0 * f["seconds"] for f in frames if "seconds" in f]
    return {"rss_kb": usage.ru_maxrss, "build_s": float(m.group(2)),
            "triangles": int(m.group(1)),
            "frame_ms": statistics.median(frame_ms) if frame_ms else None, "exr": exr}


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("base_bin", help="a build's bin/ from before instancing")
    p.add_argument("new_bin", help="a build's bin/ with instancing")
    p.add_argument("--scene", default=DEFAULT_SCENE)
    p.add_argument("--runs", type=int, default=3)
    p.add_argument("--frames", type=int, default=2)
    p.add_argument("--width", type=int, default=320)
    p.add_argument("--height", type=int, default=240)
    p.add_argument("--threads", type=int, default=1)
    p.add_argument("--json", default=os.path.join(ROOT, "docs", "perf", "instancing.json"))
    p.add_argument("--doc", default=os.path.join(ROOT, "docs", "PERFORMANCE.md"))
    p.add_argument("--no-doc", action="store_true", help="print only; write no file")
    args = p.parse_args()
    meta = report_util.machine()
    start = time.time()
    runs = {"flattened": [], "instanced": []}
    with tempfile.TemporaryDirectory() as out:
        for r in range(args.runs):
            for name, bin_dir in (("flattened", args.base_bin), ("instanced", args.new_bin)):
                res = run_once(bin_dir, args.scene, out, f"{name}{r}", args)
                runs[name].append(res)
                print(f"{name} run {r}: client peak RSS {res['rss_kb'] / 1024:.1f} MiB, "
                      f"scene ready in {res['build_s']:.2f} s, {res['triangles']} triangles",
                      flush=True)
        # What a client takes for a scene of almost nothing (the default scene, 1,304 triangles):
        # Embree's and the render threads' own memory, the same in both builds.
        baseline = run_once(args.new_bin, os.path.join(ROOT, "scenes", "cornell", "cornell.json"),
                            out, "baseline", args)
        print(f"baseline (default scene): client peak RSS {baseline['rss_kb'] / 1024:.1f} MiB",
              flush=True)
        cmp = subprocess.run([os.path.join(args.new_bin, "igi-compare"), runs["instanced"][0]["exr"],
                              runs["flattened"][0]["exr"]], stdout=subprocess.PIPE, text=True,
                             check=True)
        rel = json.loads(cmp.stdout)["relative_mse"]
    summary = {}
    for name, rs in runs.items():
        summary[name] = {
            "rss_mib": statistics.median(r["rss_kb"] for r in rs) / 1024.0,
            "build_s": statistics.median(r["build_s"] for r in rs),
            "frame_ms": statistics.median(r["frame_ms"] for r in rs if r["frame_ms"] is not None)
            if any(r["frame_ms"] is not None for r in rs) else None,
            "triangles": rs[0]["triangles"], "runs": rs}
    f, i = summary["flattened"], summary["instanced"]
    result = {"machine": meta, "scene": os.path.relpath(args.scene, ROOT), "runs": args.runs,
              "frames": args.frames, "size": [args.width, args.height], "threads": args.threads,
              "flattened": f, "instanced": i, "relative_mse": rel,
              "baseline_rss_mib": baseline["rss_kb"] / 1024.0,
              "seconds": round(time.time() - start, 1)}
    print(json.dumps({k: v for k, v in result.items() if k not in ("flattened", "instanced")}))
    print(f"client peak RSS: {f['rss_mib']:.1f} -> {i['rss_mib']:.1f} MiB; scene build "
          f"{f['build_s']:.2f} -> {i['build_s']:.2f} s; relMSE {rel:.3g}")
    if args.no_doc:
        return
    os.makedirs(os.path.dirname(args.json), exist_ok=True)
    for s in (f, i):
        for r in s["runs"]:
            r.pop("exr", None)
    with open(args.json, "w") as out:
        json.dump(result, out, indent=1)
    frame = (lambda s: "n/a" if s["frame_ms"] is None else f"{s['frame_ms']:.0f} ms")
    body = "\n".join([
        f"Measured on {meta['date']} by `scripts/bench_instancing.sh BASE_BIN NEW_BIN` "
        f"({result['seconds']:.0f} s): {meta['cpu']}, `nproc` = {meta['nproc']}, load "
        f"`{meta['load']}` at the start; `{result['scene']}`, one client with "
        f"{args.threads} render thread(s), {args.width} x {args.height}, {args.frames} frames, "
        f"median of {args.runs} runs of each build, alternated.",
        "",
        "| | flattened (before) | instanced | ratio |",
        "|---|---:|---:|---:|",
        f"| client peak resident memory | {f['rss_mib']:.0f} MiB | {i['rss_mib']:.0f} MiB | "
        f"{f['rss_mib'] / i['rss_mib']:.1f}x less |",
        f"| the same above a client on the default scene ({result['baseline_rss_mib']:.0f} MiB) | "
        f"{f['rss_mib'] - result['baseline_rss_mib']:.0f} MiB | "
        f"{i['rss_mib'] - result['baseline_rss_mib']:.0f} MiB | "
        f"{(f['rss_mib'] - result['baseline_rss_mib']) / max(i['rss_mib'] - result['baseline_rss_mib'], 1):.0f}x less |",
        f"| scene ready (load, BVHs, first version) | {f['build_s']:.2f} s | {i['build_s']:.2f} s | "
        f"{f['build_s'] / i['build_s']:.1f}x faster |",
        f"| frame time | {frame(f)} | {frame(i)} | |",
        f"| triangles placed | {f['triangles']:,} | {i['triangles']:,} | |",
        "",
        f"The two builds' images differ by a relMSE of {rel:.2g} (transform rounding: an instance "
        "applies the node's matrix at each ray, the flattened mesh had it baked into its "
        "vertices)."])
    report_util.splice(args.doc, {"instancing": body}, lambda msg: print(msg, file=sys.stderr))


if __name__ == "__main__":
    main()
