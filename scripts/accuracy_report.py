#!/usr/bin/python3
"""Speed against accuracy of igi, and the peer comparison (docs/ACCURACY.md).

Run through scripts/bench_accuracy.sh (which installs and builds first). Steps:
  1. converged references from our path tracer, cached in --ref (reused when present);
  2. igi parameter sweeps (indirect VPLs, light samples, caustic photons, interleaving + filter)
     and accumulation (frames 1, 2, 4, ...), our own path tracer at equal time, and with --peers
     Blender Cycles (and a probe of Embree's pathtracer);
  3. every image against its scene's reference with igi-compare (relMSE, SSIM, bias);
  4. results.csv, results.md and one log-log plot per scene (error against time, Pareto front)
     in --docs; the tables between "<!-- BEGIN GENERATED -->" markers of docs/ACCURACY.md are
     replaced, the prose around them is kept.

Timing: "s/frame" is the session's render time (first frame opened to last composited, from
--stats-json) over the frames rendered; frames are pipelined, so this is throughput, not the
latency of one frame. An accumulated image of k frames costs k times that ("time"). "wall" is
the whole process, start-up of the local clients and scene shipping included.

Python 3 standard library plus matplotlib (Debian's python3-matplotlib, /usr/bin/python3).
"""

import argparse
import csv
import datetime
import json
import os
import platform
import re
import shutil
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PEERS = os.path.join(ROOT, "scripts", "peers")
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, PEERS)
import embree_scene  # noqa: E402
import igi_scene  # noqa: E402

SHARED = "/work/shared/scenes/cornell-box"
# name, scene file, whether it has mirrors or glass (caustic photons matter), camera for OBJs
SCENES = [
    ("default", os.path.join(ROOT, "scenes/cornell/cornell.json"), True),
    ("cornell-original", os.path.join(SHARED, "CornellBox-Original.obj"), False),
    ("cornell-sphere", os.path.join(SHARED, "CornellBox-Sphere.obj"), True),
]
# The shared Cornell boxes are bare OBJs; they get a scene file with this explicit camera so that
# every renderer sees the same view (the auto-framing camera would do too, but is less standard).
OBJ_CAMERA = {"position": [0, 1, 3.9], "look_at": [0, 1, 0], "up": [0, 1, 0], "fov_y": 40}


def log(msg):
    print(f"[accuracy {time.strftime('%H:%M:%S')}] {msg}", flush=True)


def run(cmd, **kw):
    t0 = time.time()
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kw)
    if proc.returncode != 0:
        raise RuntimeError(f"command failed ({proc.returncode}): {' '.join(cmd)}\n{proc.stdout[-1500:]}{proc.stderr[-1500:]}")
    return proc, time.time() - t0


class Bench:
    def __init__(self, args):
        self.args = args
        self.bin = os.path.join(args.build, "bin")
        self.work = args.out
        self.rows = []
        os.makedirs(self.work, exist_ok=True)
        os.makedirs(args.ref, exist_ok=True)

    # ---------------------------------------------------------------- scenes and references
    def scene_file(self, name, path):
        """A scene file usable by igi-master with the benchmark's camera."""
        if not path.lower().endswith(".obj"):
            return path, []
        folder = os.path.join(self.work, "scenes")
        os.makedirs(folder, exist_ok=True)
        out = os.path.join(folder, name + ".json")
        spec = {"camera": OBJ_CAMERA, "meshes": [{"file": os.path.relpath(path, folder)}]}
        with open(out, "w", encoding="utf-8") as f:
            json.dump(spec, f, indent=1)
        return out, ["--allow-outside-paths"]

    def master(self, scene, extra, out_exr, frames, stats=None, sequence=None):
        a = self.args
        stats = stats or out_exr.replace(".exr", "-stats.json")
        cmd = [os.path.join(self.bin, "igi-master"), "--scene", scene[0], *scene[1],
               "--local-clients", str(a.clients), "--width", str(a.width), "--height", str(a.height),
               "--frames", str(frames), "--output", out_exr, "--stats-json", stats,
               "--log-level", "warn", *extra]
        if sequence:
            cmd += ["--output-sequence", sequence]
        _, wall = run(cmd)
        with open(stats, encoding="utf-8") as f:
            s = json.load(f)
        return {"seconds": s["seconds"], "frames": len(s["frames"]), "wall": wall,
                "shadow_rays_per_pixel": sum(f["shadow_rays_per_pixel"] for f in s["frames"]) / max(1, len(s["frames"]))}

    def compare(self, image, reference):
        proc, _ = run([os.path.join(self.bin, "igi-compare"), image, reference])
        return json.loads(proc.stdout)

    def reference(self, name, scene):
        """Our path tracer, two independent halves (seeds 1 and 2) averaged; their difference
        estimates the reference's own noise."""
        a = self.args
        tag = f"{name}-{a.width}x{a.height}-{a.ref_spp}spp-{a.ref_frames}f"
        ref = os.path.join(a.ref, tag + ".exr")
        meta = os.path.join(a.ref, tag + ".json")
        if os.path.exists(ref) and os.path.exists(meta):
            log(f"{name}: reusing reference {ref}")
            with open(meta, encoding="utf-8") as f:
                return ref, json.load(f)
        halves, seconds = [], 0.0
        for seed in (1, 2):
            half = os.path.join(a.ref, f"{tag}-seed{seed}.exr")
            log(f"{name}: reference half {seed}: path tracer {a.ref_spp} spp x {a.ref_frames // 2} frames")
            r = self.master(scene, ["--integrator", "path", "--spp", str(a.ref_spp), "--seed", str(seed)],
                            half, a.ref_frames // 2)
            seconds += r["seconds"]
            halves.append(half)
        run(["oiiotool", halves[0], halves[1], "--add", "--mulc", "0.5", "-d", "float", "-o", ref])
        between = self.compare(halves[0], halves[1])
        info = {"spp_total": a.ref_spp * (a.ref_frames // 2) * 2, "seconds": seconds,
                # relMSE of one half against the other is about twice a half's own relMSE; the
                # mean of both has half a half's variance: floor ~ between / 4.
                "halves_relative_mse": between["relative_mse"],
                "noise_floor_relative_mse": between["relative_mse"] / 4,
                "halves_ssim": between["ssim"]}
        with open(meta, "w", encoding="utf-8") as f:
            json.dump(info, f, indent=1)
        return ref, info

    # ---------------------------------------------------------------- rows
    def add(self, **row):
        err = self.compare(row.pop("image"), row.pop("reference"))
        row.update(relmse=err["relative_mse"], ssim=err["ssim"], bias=err["mean_relative_bias"],
                   rmse=err["rmse"], block_error=err["block_relative_error"])
        self.rows.append(row)
        log(f"  {row['scene']} {row['renderer']} {row['sweep']}={row['value']}: "
            f"{row['time']*1e3:.0f} ms, relMSE {row['relmse']:.4g}, SSIM {row['ssim']:.4f}")

    def igi_sweeps(self, name, scene, ref, specular):
        a = self.args
        d = os.path.join(self.work, name)
        os.makedirs(d, exist_ok=True)
        sweeps = [
            ("indirect_vpls", "--indirect-vpls", a.vpls),
            ("direct_samples", "--direct-samples", a.direct),
        ]
        if specular:
            sweeps.append(("caustic_photons", "--caustic-photons", a.photons))
        for sweep, flag, values in sweeps:
            for v in values:
                out = os.path.join(d, f"igi-{sweep}-{v}.exr")
                r = self.master(scene, [flag, str(v), "--no-accumulate"], out, a.timing_frames)
                self.add(scene=name, renderer="igi", sweep=sweep, value=str(v), frames=1,
                         spf=r["seconds"] / r["frames"], time=r["seconds"] / r["frames"],
                         wall=r["wall"], rays=r["shadow_rays_per_pixel"], image=out, reference=ref)
        for n in a.interleave:
            out = os.path.join(d, f"igi-interleave-{n}.exr")
            r = self.master(scene, ["--interleave", f"{n}x{n}", "--filter", f"{n}x{n}", "--no-accumulate"],
                            out, a.timing_frames)
            self.add(scene=name, renderer="igi", sweep="interleave+filter", value=f"{n}x{n}", frames=1,
                     spf=r["seconds"] / r["frames"], time=r["seconds"] / r["frames"], wall=r["wall"],
                     rays=r["shadow_rays_per_pixel"], image=out, reference=ref)
        self.accumulation(name, scene, ref, "igi", [], "frames")

    def accumulation(self, name, scene, ref, renderer, extra, sweep):
        """One run of max(frames) frames, every accumulated frame written: error after k frames."""
        a = self.args
        d = os.path.join(self.work, name)
        last = max(a.frames)
        pattern = os.path.join(d, f"{renderer}-acc-%04d.exr")
        out = os.path.join(d, f"{renderer}-acc.exr")
        r = self.master(scene, extra, out, last, sequence=pattern)
        spf = r["seconds"] / r["frames"]
        for k in a.frames:
            image = pattern % (k - 1)
            self.add(scene=name, renderer=renderer, sweep=sweep, value=str(k), frames=k, spf=spf,
                     time=spf * k, wall=r["wall"], rays=r["shadow_rays_per_pixel"], image=image, reference=ref)
        for k in range(last):
            if (k + 1) not in a.frames:
                os.remove(pattern % k)

    def path_tracer(self, name, scene, ref):
        self.accumulation(name, scene, ref, "igi-path", ["--integrator", "path", "--spp", "1"], "spp")

    # ---------------------------------------------------------------- peers
    def cycles(self, name, scene_path, ref):
        a = self.args
        blender = shutil.which("blender")
        if not blender:
            self.notes.append("Blender was not found: Cycles was not run (install it with --peers).")
            return
        d = os.path.join(self.work, name)
        prefix = os.path.join(d, "cycles")
        # The shared OBJs get the benchmark camera through their generated scene file.
        cmd = [blender, "-b", "--factory-startup", "-noaudio", "-P", os.path.join(PEERS, "cycles_render.py"), "--",
               scene_path, prefix, str(a.width), str(a.height), str(os.cpu_count() or 2),
               *map(str, a.cycles_spp)]
        try:
            _, wall = run(cmd)
        except RuntimeError as e:
            self.notes.append(f"Blender Cycles failed on {name}: {str(e).splitlines()[0]}")
            return
        with open(prefix + ".json", encoding="utf-8") as f:
            res = json.load(f)
        for r in res["renders"]:
            self.add(scene=name, renderer="cycles", sweep="spp", value=str(r["spp"]), frames=1,
                     spf=r["seconds"], time=r["seconds"], wall=wall, rays=0.0, image=r["image"], reference=ref)

    def embree_probe(self, name, scene_path):
        """Embree's pathtracer tutorial (3.13) drops quad and triangle lights when it converts its
        scene graph ('not implemented'), so area-lit scenes render black. This probe renders the
        scene with its area lights and records the image's mean, so the document states a
        measured fact rather than a reading of the source."""
        exe = shutil.which("pathtracer")
        if not exe:
            return None
        d = os.path.join(self.work, name)
        flat = igi_scene.flatten(scene_path, self.args.width, self.args.height)
        xml = os.path.join(d, "embree.xml")
        embree_scene.write(flat, xml, 1.0)
        pfm = os.path.join(d, "embree-probe.pfm")
        _, wall = run([exe, "-i", xml, *embree_scene.camera_args(flat), "--size", str(self.args.width),
                       str(self.args.height), "--spp", "4", "--max-path-length", "16",
                       "--threads", str(os.cpu_count() or 2), "-o", pfm])
        proc, _ = run(["oiiotool", pfm, "--printstats"])
        m = re.search(r"Stats Avg:\s*([-\d.e]+)\s+([-\d.e]+)\s+([-\d.e]+)", proc.stdout)
        mean = sum(float(x) for x in m.groups()) / 3 if m else float("nan")
        return {"scene": name, "mean": mean, "wall": wall}

    # ---------------------------------------------------------------- all
    def run_all(self):
        a = self.args
        self.notes = []
        self.refs = {}
        self.probes = []
        for name, path, specular in SCENES:
            if a.scenes and name not in a.scenes:
                continue
            if not os.path.exists(path):
                log(f"{name}: {path} is missing, skipped")
                self.notes.append(f"{name} skipped: {path} missing")
                continue
            scene = self.scene_file(name, path)
            ref, info = self.reference(name, scene)
            self.refs[name] = info
            log(f"{name}: reference noise floor relMSE ~ {info['noise_floor_relative_mse']:.2g}")
            self.igi_sweeps(name, scene, ref, specular)
            self.path_tracer(name, scene, ref)
            if a.peers:
                self.cycles(name, scene[0], ref)
                probe = self.embree_probe(name, scene[0])
                if probe:
                    self.probes.append(probe)


# -------------------------------------------------------------------- reporting
def pareto(points):
    """Indices of the points no other point beats in both time and error."""
    order = sorted(range(len(points)), key=lambda i: (points[i][0], points[i][1]))
    front, best = [], float("inf")
    for i in order:
        if points[i][1] < best:
            front.append(i)
            best = points[i][1]
    return front


def mark_pareto(rows):
    for scene in sorted({r["scene"] for r in rows}):
        sub = [r for r in rows if r["scene"] == scene]
        for i in pareto([(r["time"], r["relmse"]) for r in sub]):
            sub[i]["pareto"] = True
    for r in rows:
        r.setdefault("pareto", False)


STYLE = {
    ("igi", "indirect_vpls"): ("o", "tab:blue", "igi: indirect VPLs per set"),
    ("igi", "direct_samples"): ("s", "tab:orange", "igi: light samples"),
    ("igi", "caustic_photons"): ("^", "tab:purple", "igi: caustic photons per set"),
    ("igi", "interleave+filter"): ("D", "tab:brown", "igi: interleave = filter (1x1..4x4)"),
    ("igi", "frames"): ("o", "tab:red", "igi: accumulated frames (default settings)"),
    ("igi-path", "spp"): ("x", "tab:gray", "our path tracer, 1 spp per frame, accumulated"),
    ("cycles", "spp"): ("v", "tab:green", "Blender Cycles (CPU), samples per pixel"),
}


def plot(rows, scene, path, refinfo):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    sub = [r for r in rows if r["scene"] == scene]
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.2))
    for ax, key, label in ((axes[0], "relmse", "relative MSE"), (axes[1], "dssim", "1 - SSIM")):
        for (renderer, sweep), (marker, colour, name) in STYLE.items():
            pts = sorted([r for r in sub if r["renderer"] == renderer and r["sweep"] == sweep], key=lambda r: r["time"])
            if not pts:
                continue
            ys = [r["relmse"] if key == "relmse" else max(1e-5, 1 - r["ssim"]) for r in pts]
            line = "-" if sweep in ("frames", "spp") else ":"
            ax.plot([r["time"] for r in pts], ys, line, marker=marker, color=colour, label=name, alpha=0.85)
            for r, y in zip(pts, ys):
                ax.annotate(r["value"], (r["time"], y), fontsize=6, xytext=(3, 3), textcoords="offset points")
        if key == "relmse":
            front = sorted([r for r in sub if r["pareto"]], key=lambda r: r["time"])
            xs, ys = [], []
            for r in front:
                if xs:
                    xs.append(r["time"])
                    ys.append(ys[-1])
                xs.append(r["time"])
                ys.append(r["relmse"])
            ax.plot(xs, ys, "k--", lw=1, label="Pareto front (all points)")
            ax.scatter([r["time"] for r in front], [r["relmse"] for r in front], s=90, facecolors="none",
                       edgecolors="k", zorder=5)
            floor = refinfo.get("noise_floor_relative_mse")
            if floor:
                ax.axhline(floor, color="k", lw=0.6, alpha=0.5)
                ax.annotate("reference noise", (ax.get_xlim()[0], floor), fontsize=7, xytext=(2, 2),
                            textcoords="offset points")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("render time of the image, seconds (log)")
        ax.set_ylabel(label + " (log)")
        ax.grid(True, which="both", alpha=0.3)
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=8)
    fig.suptitle(f"{scene}: error against time (reference: our path tracer, {refinfo.get('spp_total', '?')} spp)")
    fig.tight_layout(rect=(0, 0.1, 1, 1))
    fig.savefig(path, dpi=110)
    plt.close(fig)


def fmt(x, digits=3):
    return f"{x:.{digits}g}"


def table(rows, scene):
    sub = [r for r in rows if r["scene"] == scene]
    lines = ["| renderer | parameter | value | frames | s/frame | time (s) | wall (s) | shadow rays/px | relMSE | SSIM | bias | Pareto |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in sub:
        lines.append(f"| {r['renderer']} | {r['sweep']} | {r['value']} | {r['frames']} | {fmt(r['spf'])} | "
                     f"{fmt(r['time'])} | {r['wall']:.1f} | {r['rays']:.1f} | {fmt(r['relmse'])} | {r['ssim']:.4f} | "
                     f"{r['bias']:+.3f} | {'**yes**' if r['pareto'] else ''} |")
    return "\n".join(lines)


def machine():
    cpu = "?"
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return {"nproc": os.cpu_count(), "cpu": cpu, "date": datetime.datetime.now().isoformat(timespec="seconds"),
            "load": " ".join(f"{x:.2f}" for x in os.getloadavg()), "kernel": platform.release()}


def write_reports(bench, docs, command, started):
    rows = bench.rows
    mark_pareto(rows)
    os.makedirs(docs, exist_ok=True)
    fields = ["scene", "renderer", "sweep", "value", "frames", "spf", "time", "wall", "rays", "relmse", "ssim",
              "bias", "rmse", "block_error", "pareto"]
    with open(os.path.join(docs, "results.csv"), "w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        for r in rows:
            w.writerow({k: r[k] for k in fields})
    end = machine()
    a = bench.args
    parts = {}
    parts["machine"] = "\n".join([
        f"- command: `{command}`",
        f"- machine: {end['nproc']} cores ({end['cpu']}), kernel {end['kernel']}",
        f"- started {started['date']} (load average {started['load']}), finished {end['date']} (load {end['load']})",
        f"- resolution {a.width} x {a.height}, {a.clients} local clients; sweep points rendered "
        f"{a.timing_frames} frames each without accumulation (time per frame = throughput)",
        "- the machine's two cores are shared with other work: timings carry that noise",
    ])
    refs = ["| scene | reference spp | reference time (s) | noise floor relMSE (halves / 4) | SSIM between halves |",
            "|---|---|---|---|---|"]
    for scene, info in bench.refs.items():
        refs.append(f"| {scene} | {info['spp_total']} | {info['seconds']:.0f} | {fmt(info['noise_floor_relative_mse'])} | "
                    f"{info['halves_ssim']:.4f} |")
    parts["references"] = "\n".join(refs)
    scene_parts = []
    for scene in bench.refs:
        png = f"{scene}.png"
        plot(rows, scene, os.path.join(docs, png), bench.refs[scene])
        scene_parts.append(f"### {scene}\n\n![{scene}: error against time](accuracy/{png})\n\n{table(rows, scene)}\n")
    parts["results"] = "\n".join(scene_parts)
    notes = list(bench.notes)
    for p in bench.probes:
        notes.append(f"Embree pathtracer probe on {p['scene']} (scene with its area lights, 4 spp): "
                     f"image mean {p['mean']:.4g} (0 = black: its area lights are not rendered).")
    parts["notes"] = "\n".join(f"- {n}" for n in notes) if notes else "- none"
    with open(os.path.join(docs, "results.md"), "w", encoding="utf-8") as f:
        for key in ("machine", "references", "results", "notes"):
            f.write(f"## {key}\n\n{parts[key]}\n\n")
    with open(os.path.join(docs, "summary.json"), "w", encoding="utf-8") as f:
        json.dump({"machine_start": started, "machine_end": end, "references": bench.refs, "notes": notes,
                   "pareto": [r for r in rows if r["pareto"]]}, f, indent=1)
    return parts


def splice(doc_path, parts):
    """Replaces <!-- BEGIN GENERATED key --> ... <!-- END GENERATED key --> blocks."""
    if not os.path.exists(doc_path):
        return
    with open(doc_path, encoding="utf-8") as f:
        text = f.read()
    for key, body in parts.items():
        pattern = re.compile(rf"(<!-- BEGIN GENERATED {key} -->\n).*?(<!-- END GENERATED {key} -->)", re.S)
        text = pattern.sub(lambda m: m.group(1) + body + "\n" + m.group(2), text)
    with open(doc_path, "w", encoding="utf-8") as f:
        f.write(text)


def ints(s):
    return [int(x) for x in s.split(",") if x]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    p.add_argument("--out", default=os.path.join(ROOT, "out", "accuracy"), help="images and runs (not in git)")
    p.add_argument("--ref", default=os.path.join(ROOT, "out", "reference"), help="cached references (not in git)")
    p.add_argument("--docs", default=os.path.join(ROOT, "docs", "accuracy"), help="tables and plots; '' for none")
    p.add_argument("--doc", default=os.path.join(ROOT, "docs", "ACCURACY.md"), help="document whose generated blocks are replaced")
    p.add_argument("--quick", action="store_true", help="smoke run: default scene, few points, weak reference")
    p.add_argument("--peers", action="store_true", help="also Blender Cycles and the Embree pathtracer probe")
    p.add_argument("--scenes", default="", help="comma-separated subset of: " + ", ".join(s[0] for s in SCENES))
    p.add_argument("--width", type=int, default=320)
    p.add_argument("--height", type=int, default=240)
    p.add_argument("--clients", type=int, default=2)
    p.add_argument("--command", default="scripts/bench_accuracy.sh", help="the command line recorded in the document")
    a = p.parse_args()
    a.scenes = [s for s in a.scenes.split(",") if s]
    if a.quick:
        a.scenes = a.scenes or ["default"]
        a.vpls, a.direct, a.photons, a.interleave = [6, 18, 54], [1, 4, 16], [0, 500], [1, 3]
        a.frames, a.cycles_spp, a.timing_frames = [1, 2, 4, 8], [1, 4], 2
        a.ref_spp, a.ref_frames = 16, 8
    else:
        a.vpls, a.direct, a.photons, a.interleave = [2, 6, 18, 54, 162], [1, 2, 4, 8, 16], [0, 100, 500, 2000, 8000], [1, 2, 3, 4]
        a.frames, a.cycles_spp, a.timing_frames = [1, 2, 4, 8, 16, 32, 64], [1, 2, 4, 8, 16, 32, 64], 4
        a.ref_spp, a.ref_frames = 32, 32
    started = machine()
    bench = Bench(a)
    bench.run_all()
    if not bench.rows:
        raise SystemExit("no scene was rendered")
    docs = a.docs if a.docs else os.path.join(a.out, "report")
    parts = write_reports(bench, docs, a.command, started)
    if a.docs and not a.quick:
        splice(a.doc, parts)
    log(f"wrote {docs}/results.md, results.csv and plots")


if __name__ == "__main__":
    main()
