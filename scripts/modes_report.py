#!/usr/bin/python3
"""The GI modes while things move (docs/MODES.md, "Measurements").

Run through scripts/bench_modes.sh (which installs and builds first). For each animation of
scenes/cornell/ (example.anim.json, moving-light.anim.json, jump.anim.json):
  1. a path-traced reference of every frame's scene state: our path tracer (--integrator path,
     --ref-spp samples per pixel per frame, a quarter of it for jump.anim.json, whose still
     epochs accumulate) on the same animation at the same size, cached in
     --ref-dir/<scene>-<anim>-<W>x<H>-<spp>spp-f<frames>-<hash of scene, meshes and animation>/
     and reused when present. The session accumulates while the scene holds still, so the
     reference of a frame is the image at the last frame of its scene epoch: a frame whose
     state lasts n frames has an n x spp reference (the still parts of jump.anim.json), a frame
     of a moving scene an spp one. Frame 0 is rendered once more with another seed: half the
     relMSE between the two is the reference's own noise at spp (its "floor"; n x spp: floor / n);
  2. every mode of --modes (a mode this igi-master's --gi rejects is skipped, with a message)
     with --no-accumulate (each frame alone: what a user sees while things move), one session
     per seed of --seeds, every frame written (--output-sequence) with --stats-json;
  3. per frame and mode: relMSE and mean bias against that frame's reference, computed as
     igi-compare does (numpy here: igi-compare takes ~0.4 s an image; it checks the first and
     last frame of every session), the mean over the seeds;
  4. flicker, per consecutive pair (t-1, t) of frames whose camera did not move (from the
     animation's camera keyframes): the static mask holds the pixels whose references agree,
     |L_t - L_t-1| <= 2 % of the larger plus 0.5 % of the image's mean, L the luminance (mean of
     R, G, B) of the references blurred 3 x 3 (which divides their noise by about 3), and no
     channel of either reference above 1 (white on screen: the light itself); over the
     mask, flicker = mean |frame_t - frame_t-1| / mean reference (pairs whose mask holds under
     1 % of the pixels, or whose mask is darker than 10 % of the animation's mean reference, the
     light being off, are skipped). The references' own flicker on the same mask (their noise
     and what changed by less than the threshold) is reported beside it;
  5. lag, after each change that follows at least 4 frames of a still scene (jump.anim.json's
     frame 8): the still level is a mode's mean relMSE over the still frames before the change,
     each against its own reference; lag = frames from the change until the relMSE is under
     1.5 x that level (0: the changed frame itself is), "never" if it is not before the end;
  6. time per frame (the session's render time over its frames: throughput, from
     --stats-json; the median latency of one frame beside it) and rays per frame (the clients'
     count per tile: eye, shadow and light-set building rays);
  7. docs/modes/ (results.csv, results.md, summary.json, one error plot per animation, the
     flicker plot) and the block between "<!-- BEGIN GENERATED modes -->" and
     "<!-- END GENERATED modes -->" of docs/MODES.md (the prose around it is kept); a summary
     per animation and mode is printed at the end.

With --quick: the first --max-frames (20) frames of each animation, a 128-spp reference, one
seed; everything goes to out/modes-quick/ and docs/ are not touched.

Python 3 standard library plus matplotlib and numpy (Debian's python3-matplotlib and
python3-numpy, /usr/bin/python3).
"""

import argparse
import csv
import hashlib
import json
import math
import os
import re
import shutil
import statistics
import struct
import subprocess
import sys
import time
import zlib

import numpy as np

import report_util
from report_util import machine, num, run


ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.dont_write_bytecode = True  # no __pycache__ in the source tree

SCENE = os.path.join(ROOT, "scenes", "cornell", "cornell.json")
# (name, file, what moves, reference spp per frame = --ref-spp / this): jump.anim.json has two
# still epochs of 8 and 24 frames whose references accumulate, so a quarter per frame is plenty.
ANIMS = [
    ("example", "scenes/cornell/example.anim.json",
     "the example: camera, glass ball, mirror box, the quad light (moving, turning blue, off for 4 frames) "
     "and the red wall's colour all animated; the camera holds still from frame 12 to 32", 1),
    ("moving-light", "scenes/cornell/moving-light.anim.json",
     "the ceiling light slides along the ceiling and back; camera and objects still", 1),
    ("jump", "scenes/cornell/jump.anim.json",
     "all still; the mirror box jumps to the front at frame 8 and stays there", 4),
]
ANIM_NAMES = [a[0] for a in ANIMS]
DEFAULT_MODES = "igi,spt,stream,spt-eq,stream-eq,cache,photonmap"
# Modes at settings of their own: the name, then the --gi mode and its options. The "-eq" ones
# shrink the pool to about IGI's shadow rays a pixel (4 light samples + about 8 VPLs a set), so
# that they run at about IGI's time per frame: spt with 2 paths a group (72 paths) instead of 3,
# stream with 100 surface lights instead of 256.
MODE_VARIANTS = {
    "spt-eq": ("spt", ["--spt-paths", "2"]),
    "stream-eq": ("stream", ["--stream-vsls", "100"]),
}


def gi_of(mode):
    """The --gi value and the extra options of a mode of --modes."""
    return MODE_VARIANTS.get(mode, (mode, []))

# Static mask and flicker.
DARK_FRACTION = 0.1  # pairs whose static region is darker than this share of the mean: light off
MASK_REL = 0.02  # references agree within 2 % of the larger ...
MASK_ABS = 0.005  # ... plus 0.5 % of the image's mean
MASK_MIN_FRACTION = 0.01  # a pair whose mask holds fewer pixels is skipped
MASK_WHITE = 1.0  # pixels whose reference exceeds this in a channel are left out (white on screen)
# Lag.
LAG_FACTOR = 1.5
LAG_MIN_STILL = 4  # frames of a still scene before a change for its lag to be measured
# "At equal time per frame": modes whose seconds per frame differ by more are called out.
EQUAL_TIME_TOLERANCE = 0.20

# The papers' own claims (docs/MODES.md lists the papers).
PAPERS = [
    {"paper": "004 IGI, Wald et al. 2002", "mode": "igi",
     "hardware": "cluster of dual AthlonMP 1800+ PCs (8 clients; 12 for the conference room), "
                 "100 Mbit Ethernet, Gigabit uplink to the master (sec. 5)",
     "setting": "640 x 480, 3 x 3 interleaving and discontinuity buffer",
     "speed": "room with glass ball 3.3 fps (22 shadow rays/px, 500 caustic photons per frame), "
              "office 2.2 fps, conference room 1.7 fps (sec. 5.1)",
     "lag": "none by design: fresh VPLs every frame; converged image 1-2 s after interaction stops (sec. 5.1)",
     "flicker": "qualitative only: 'minimal' in the simple scenes, 'noticeable' in the office (sec. 5.1, 5.2)",
     "error": "no image-error numbers"},
    {"paper": "000 SPT, Dmitriev et al. 2002", "mode": "spt",
     "hardware": "one 1.7 GHz dual P4 Xeon PC + GeForce3 64 MB (sec. 7)",
     "setting": "ROOM (12,400 mesh elements, 4 lights), HOUSE (377,900, 2 lights); direct light and display on the GPU",
     "speed": "ROOM 8 fps, HOUSE 1.1 fps (display rate; indirect light is refined more slowly) (sec. 7)",
     "lag": "full recovery after furniture moves: ROOM 2-4 s, HOUSE 4-8 s (sec. 7)",
     "flicker": "not measured",
     "error": "no image-error numbers; tracing changed paths twice costs on average below 25 % (sec. 7)"},
    {"paper": "001 Photon Streaming, Meneveaux and Bridault 2008", "mode": "stream",
     "hardware": "AMD Athlon 64 X2 3800+ (dual core) + GeForce 8600GT (sec. 8, 'Results')",
     "setting": "Cornell Box 2,006 polygons, one spot light; VSLs shaded without shadows (sec. 6)",
     "speed": "Cornell Box 800 x 600: 140 / 48 / 36 / 21 fps with 10 / 50 / 100 / 200 VSLs (deferred shading, "
              "Table 2); 1280 x 1024: 55 / 19 / 15 / 8 fps (Table 3); 20 fps while the light and sphere move (Fig. 11)",
     "lag": "'some latency' that depends on the pool size and the number of VSLs, no figure (sec. 8, 9.1)",
     "flicker": "not measured",
     "error": "no image-error numbers ('does not provide an exact solution at each frame', sec. 9.1)"},
    {"paper": "003 Instant Caching, Debattista et al. 2009", "mode": "cache",
     "hardware": "one PC, 8 cores (dual quad-core, 3 GHz), ray tracing on the CPU (sec. 4)",
     "setting": "Cornell Box (about 65K triangles, a bunny circling a statue), Desk, Conference, Sibenik, Office ...; "
                "diffuse interreflections from VPLs",
     "speed": "first frame 1.49-3.62 x faster than IGI (Table 1); animations 2.42-6.82 x IGI's fps, "
              "Cornell Box 10.45 fps against IGI's 2.11 (Table 3)",
     "lag": "none claimed: invalid records are recomputed in the frame (sec. 3.2)",
     "flicker": "not measured",
     "error": "HDR-VDP against 2,500-spp path tracing: at most 2.11 % of pixels perceptibly different "
              "(P > 75 %), 0-0.33 % against IGI (Table 5)"},
    {"paper": "002 Simulated photon mapping, Larsen and Christensen 2004", "mode": "photonmap",
     "hardware": "Pentium 4 2.4 GHz + GeForce FX 5950 (sec. 8)",
     "setting": "box with a dynamic cube and sphere, 512 x 512; 77 groups x 40 photons, 140 AIM and 140 IIM "
                "texels, 20 final-gathered texels a frame, 10,000 caustic photons renewed over 8 frames",
     "speed": "35+ fps (sec. 8)",
     "lag": "photons retraced every 8 frames; 'a trail after the specular object' when it moves fast (sec. 4)",
     "flicker": "not measured",
     "error": "no image-error numbers"},
]


def log(msg):
    print(f"[modes {time.strftime('%H:%M:%S')}] {msg}", flush=True)


class ModeRejected(RuntimeError):
    pass


# -------------------------------------------------------------------- EXR
def _cstr(data, pos):
    end = data.index(b"\0", pos)
    return data[pos:end].decode("latin-1"), end + 1


def _exr_native(path):
    """A scanline OpenEXR file with NONE, ZIPS or ZIP compression (what igi-master writes) as an
    H x W x 3 float32 array (R, G, B); None for any other kind of file."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] != b"\x76\x2f\x31\x01":
        return None
    flags = struct.unpack_from("<I", data, 4)[0] >> 8
    if flags & (0x02 | 0x08 | 0x10):  # tiled, deep, multi-part
        return None
    pos, attrs = 8, {}
    while data[pos] != 0:
        name, pos = _cstr(data, pos)
        typ, pos = _cstr(data, pos)
        size = struct.unpack_from("<i", data, pos)[0]
        pos += 4
        attrs[name] = (typ, data[pos:pos + size])
        pos += size
    pos += 1
    channels, cpos, chl = [], 0, attrs["channels"][1]
    while chl[cpos] != 0:
        cname, cpos = _cstr(chl, cpos)
        ptype, _, _, _, _, xs, ys = struct.unpack_from("<iBBBBii", chl, cpos)
        cpos += 16
        if xs != 1 or ys != 1:
            return None
        channels.append((cname, {0: np.dtype("<u4"), 1: np.dtype("<f2"), 2: np.dtype("<f4")}[ptype]))
    compression = attrs["compression"][1][0]
    if compression not in (0, 2, 3):
        return None
    xmin, ymin, xmax, ymax = struct.unpack("<iiii", attrs["dataWindow"][1])
    w, h = xmax - xmin + 1, ymax - ymin + 1
    per_block = 16 if compression == 3 else 1
    blocks = (h + per_block - 1) // per_block
    offsets = struct.unpack_from(f"<{blocks}Q", data, pos)
    line_bytes = sum(w * dt.itemsize for _, dt in channels)
    planes = {c: np.zeros((h, w), np.float32) for c, _ in channels}
    for off in offsets:
        y, size = struct.unpack_from("<ii", data, off)
        chunk = data[off + 8:off + 8 + size]
        lines = min(per_block, ymax + 1 - y)
        if compression and size < lines * line_bytes:
            t = np.frombuffer(zlib.decompress(chunk), np.uint8).astype(np.int64)
            t[1:] -= 128
            t = (np.cumsum(t) & 0xFF).astype(np.uint8)
            half = (len(t) + 1) // 2
            raw = np.empty(len(t), np.uint8)
            raw[0::2], raw[1::2] = t[:half], t[half:]
            raw = raw.tobytes()
        else:
            raw = chunk
        p = 0
        for ly in range(lines):
            for cname, dt in channels:
                n = w * dt.itemsize
                planes[cname][y - ymin + ly] = np.frombuffer(raw, dt, w, p).astype(np.float32)
                p += n
    if not all(c in planes for c in "RGB"):
        return None
    return np.stack([planes["R"], planes["G"], planes["B"]], axis=-1)


def read_exr(path, scratch):
    img = _exr_native(path)
    if img is None:
        # Another EXR flavour: oiiotool makes it a plain uncompressed float one first.
        tmp = os.path.join(scratch, "convert.exr")
        run(["oiiotool", path, "--ch", "R,G,B", "-d", "float", "--compression", "none", "-o", tmp])
        img = _exr_native(tmp)
        if img is None:
            raise RuntimeError(f"{path}: cannot read this EXR")
    return img


def blur3(lum):
    p = np.pad(lum, 1, mode="edge")
    h, w = lum.shape
    return sum(p[dy:dy + h, dx:dx + w] for dy in range(3) for dx in range(3)) / 9.0


# -------------------------------------------------------------------- animation
def anim_length(anim):
    last = 0
    for key in ("camera",):
        for k in anim.get(key, []):
            last = max(last, k["frame"])
    for key in ("objects", "lights", "materials"):
        for keys in anim.get(key, {}).values():
            for k in keys:
                last = max(last, k["frame"])
    return last + 1


def keyed_value(keys, prop, frame):
    """docs/ANIMATION.md's interpolation of one property (numbers and vectors)."""
    named = [k for k in keys if prop in k]
    if not named:
        return None
    if frame <= named[0]["frame"]:
        return named[0][prop]
    if frame >= named[-1]["frame"]:
        return named[-1][prop]
    for a, b in zip(named, named[1:]):
        if a["frame"] <= frame <= b["frame"]:
            w = (frame - a["frame"]) / (b["frame"] - a["frame"])
            va, vb = a[prop], b[prop]
            if isinstance(va, list):
                return [x + w * (y - x) for x, y in zip(va, vb)]
            return va + w * (vb - va)
    return named[-1][prop]


def camera_moved(anim, t):
    """Whether the camera differs between frames t - 1 and t."""
    keys = anim.get("camera", [])
    for prop in ("position", "look_at", "up", "fov_y"):
        a, b = keyed_value(keys, prop, t - 1), keyed_value(keys, prop, t)
        if a is None:
            continue
        va = a if isinstance(a, list) else [a]
        vb = b if isinstance(b, list) else [b]
        if any(abs(x - y) > 1e-9 for x, y in zip(va, vb)):
            return True
    return False


def files_digest(scene_path, anim_path):
    h = hashlib.sha1()
    paths = [scene_path, anim_path]
    try:
        with open(scene_path, encoding="utf-8") as f:
            scene = json.load(f)
        folder = os.path.dirname(scene_path)
        for m in scene.get("meshes", []):
            obj = os.path.join(folder, m["file"])
            paths.append(obj)
            mtl = os.path.splitext(obj)[0] + ".mtl"
            if os.path.exists(mtl):
                paths.append(mtl)
    except (OSError, ValueError, KeyError):
        pass
    for p in paths:
        if os.path.exists(p):
            with open(p, "rb") as f:
                h.update(f.read())
    return h.hexdigest()[:10]


# -------------------------------------------------------------------- the bench
class Bench:
    def __init__(self, args):
        self.a = args
        self.bin = os.path.join(args.build, "bin")
        self.rows = []  # one per (animation, mode, frame)
        self.refs = {}  # animation -> reference info
        self.runs = {}  # (animation, mode) -> session info
        self.skipped = {}  # mode -> why
        self.notes = []
        self.anims = {}
        self.gi_choices = self.master_gi_choices()
        os.makedirs(args.out, exist_ok=True)
        self.scratch = os.path.join(args.out, "tmp")
        os.makedirs(self.scratch, exist_ok=True)

    def master_gi_choices(self):
        exe = os.path.join(self.bin, "igi-master")
        if not os.access(exe, os.X_OK):
            raise SystemExit(f"{exe} is missing: build first (scripts/setup.sh) or set IGI_BUILD")
        proc = subprocess.run([exe, "--help"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        m = re.search(r"--gi\s+TEXT:\{([^}]*)\}", proc.stdout)
        return [x.strip() for x in m.group(1).split(",")] if m else None

    def master(self, anim_path, frames, extra, folder, seed):
        a = self.a
        os.makedirs(folder, exist_ok=True)
        for n in os.listdir(folder):
            if re.match(r"frame_\d+\.exr$", n):
                os.remove(os.path.join(folder, n))
        stats = os.path.join(folder, "stats.json")
        cmd = [os.path.join(self.bin, "igi-master"), "--scene", a.scene, "--animation", anim_path,
               "--frames", str(frames), "--local-clients", str(a.clients), "--width", str(a.width),
               "--height", str(a.height), "--seed", str(seed), "--output-sequence",
               os.path.join(folder, "frame_%04d.exr"), "--stats-json", stats, "--log-level", "error", *extra]
        t0 = time.time()
        proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        wall = time.time() - t0
        if proc.returncode != 0:
            text = proc.stdout[-1500:] + proc.stderr[-1500:]
            # CLI11's refusal of a choice: "--gi: spt not in {igi,stream}".
            m = re.search(r"[^\n]*--gi\b[^\n]*(not in|invalid|unknown)[^\n]*", text, re.I)
            if m:
                raise ModeRejected(m.group(0).strip())
            raise RuntimeError(f"command failed ({proc.returncode}): {' '.join(cmd)}\n{text}")
        with open(stats, encoding="utf-8") as f:
            s = json.load(f)
        fr = sorted(s["frames"], key=lambda x: x["index"])
        if len(fr) != frames:
            raise RuntimeError(f"{folder}: {len(fr)} frames in the statistics, {frames} asked for")
        return {"seconds": s["seconds"], "wall": wall, "frames": fr,
                "images": [os.path.join(folder, f"frame_{i:04d}.exr") for i in range(frames)]}

    def compare(self, image, reference):
        proc, _ = run([os.path.join(self.bin, "igi-compare"), image, reference])
        return json.loads(proc.stdout)

    def errors(self, images, refs, paths, ref_paths):
        """relMSE, mean bias and RMSE of each image against its reference, as igi-compare computes
        them (common/image/ImageCompare.cpp), here with numpy: igi-compare takes ~0.4 s an image.
        The first and the last frame are checked against igi-compare itself."""
        out = []
        for img, ref in zip(images, refs):
            d = img.astype(np.float64) - ref
            sr = float(ref.sum())
            out.append({"relative_mse": float((d * d / (ref.astype(np.float64) ** 2 + 0.01)).mean()),
                        "mean_relative_bias": float(img.sum(dtype=np.float64)) / sr - 1.0 if sr > 0 else 0.0,
                        "rmse": float(np.sqrt((d * d).mean()))})
        for t in sorted({0, len(images) - 1}):
            c = self.compare(paths[t], ref_paths[t])
            for key in ("relative_mse", "mean_relative_bias", "rmse"):
                if abs(c[key] - out[t][key]) > 1e-4 * max(1.0, abs(c[key])):
                    raise RuntimeError(f"{paths[t]}: {key} {out[t][key]:.6g} here, {c[key]:.6g} from igi-compare: "
                                       "the EXR reading or the error formula is out of step with igi-compare")
        return out

    # ---------------------------------------------------------------- reference
    def reference(self, name, anim_path, frames, spp):
        a = self.a
        digest = files_digest(a.scene, anim_path)
        scene_name = os.path.splitext(os.path.basename(a.scene))[0]
        tag = f"{scene_name}-{name}-{a.width}x{a.height}-{spp}spp-f{frames}-{digest}"
        folder = os.path.join(a.ref_dir, tag)
        meta_path = os.path.join(folder, "meta.json")
        if os.path.exists(meta_path):
            with open(meta_path, encoding="utf-8") as f:
                meta = json.load(f)
            if all(os.path.exists(os.path.join(folder, f"frame_{i:04d}.exr")) for i in range(frames)):
                log(f"{name}: reusing the reference {folder}")
                meta["cached"] = True
                return folder, meta
        log(f"{name}: reference: path tracer {spp} spp x {frames} frames at {a.width}x{a.height} "
            f"(about {spp * frames * a.width * a.height / 1.5e6:.0f} s at 1.5 M samples/s)")
        if os.path.isdir(folder):
            shutil.rmtree(folder)
        r = self.master(anim_path, frames, ["--integrator", "path", "--spp", str(spp)], folder, 1001)
        epochs = [f["epoch"] for f in r["frames"]]
        # The reference of frame t: the last (most accumulated) image of t's epoch.
        last_of = {}
        for i, e in enumerate(epochs):
            last_of[e] = i
        first_of = {}
        for i, e in enumerate(reversed(epochs)):
            first_of[e] = len(epochs) - 1 - i
        ref_frame = [last_of[e] for e in epochs]
        ref_spp = [spp * (last_of[e] - first_of[e] + 1) for e in epochs]
        log(f"{name}: reference noise: frame 0 once more with another seed")
        noise = self.master(anim_path, 1, ["--integrator", "path", "--spp", str(spp), "--no-accumulate"],
                            os.path.join(folder, "noise"), 1002)
        between = self.compare(r["images"][0], noise["images"][0])
        meta = {"folder": folder, "spp": spp, "frames": frames, "seconds": r["seconds"], "wall": r["wall"],
                "seconds_per_frame": r["seconds"] / frames, "epochs": epochs, "ref_frame": ref_frame,
                "ref_spp": ref_spp,
                # Two independent frames of spp each: their relMSE is about twice each one's.
                "floor_relative_mse": between["relative_mse"] / 2,
                "rays_per_frame": statistics.mean(f["rays"] for f in r["frames"]), "cached": False}
        with open(meta_path, "w", encoding="utf-8") as f:
            json.dump(meta, f, indent=1)
        return folder, meta

    # ---------------------------------------------------------------- modes
    def mode_available(self, mode):
        gi = gi_of(mode)[0]
        if self.gi_choices is not None and gi not in self.gi_choices:
            return f"this igi-master's --gi accepts only {{{','.join(self.gi_choices)}}}"
        return ""

    def run_animation(self, name, rel_path, what, ref_spp):
        a = self.a
        anim_path = os.path.join(ROOT, rel_path)
        if not os.path.exists(anim_path):
            raise RuntimeError(f"{anim_path} is missing")
        with open(anim_path, encoding="utf-8") as f:
            anim = json.load(f)
        full = anim_length(anim)
        frames = min(full, a.max_frames) if a.max_frames else full
        self.anims[name] = {"file": rel_path, "what": what, "frames": frames, "length": full}
        folder, ref = self.reference(name, anim_path, frames, ref_spp)
        self.refs[name] = ref
        ref_images = [os.path.join(folder, f"frame_{ref['ref_frame'][t]:04d}.exr") for t in range(frames)]
        log(f"{name}: {frames} frames; reference {ref['spp']} spp/frame, {ref['seconds_per_frame']:.2f} s/frame, "
            f"noise floor relMSE {ref['floor_relative_mse']:.3g} at {ref['spp']} spp")

        # Reference images, static masks and the references' own flicker.
        refs = [read_exr(p, self.scratch) for p in ref_images]
        pairs = {}  # t -> (mask, denominator, reference flicker) or the reason it is skipped
        # A pair whose static region is nearly black (the light off) is no place to see flicker:
        # a mode that still shows light there is late to follow the light (its error says so),
        # and dividing by the black reference would make that any number at all.
        animation_mean = statistics.mean(float(r.mean()) for r in refs)
        for t in range(1, frames):
            if camera_moved(anim, t):
                pairs[t] = "camera moved"
                continue
            ra, rb = refs[t - 1], refs[t]
            la, lb = blur3(ra.mean(axis=2)), blur3(rb.mean(axis=2))
            floor = MASK_ABS * 0.5 * (la.mean() + lb.mean())
            mask = np.abs(la - lb) <= MASK_REL * np.maximum(la, lb) + floor
            # White on screen (the light, its reflections): no flicker can be seen there, and an
            # emitter's radiance would swamp the mean the flicker is divided by.
            mask &= (ra.max(axis=2) <= MASK_WHITE) & (rb.max(axis=2) <= MASK_WHITE)
            frac = float(mask.mean())
            if frac < MASK_MIN_FRACTION:
                pairs[t] = f"static mask {100 * frac:.2g} % of the pixels"
                continue
            denom = float((0.5 * (ra + rb)).mean(axis=2)[mask].mean())
            if denom <= DARK_FRACTION * animation_mean:
                pairs[t] = f"static mask darker than {100 * DARK_FRACTION:.0f} % of the animation's mean (light off)"
                continue
            ref_flicker = float(np.abs(rb - ra).mean(axis=2)[mask].mean()) / denom
            pairs[t] = (mask, denom, ref_flicker, frac)

        for mode in a.modes:
            if mode in self.skipped:
                continue
            why = self.mode_available(mode)
            if why:
                self.skipped[mode] = why
                log(f"SKIPPED mode {mode}: {why}")
                continue
            per_seed = []
            for seed in a.seeds:
                out = os.path.join(a.out, name, f"{mode}-seed{seed}")
                log(f"{name}: {mode}, seed {seed}: {frames} frames, --no-accumulate")
                try:
                    gi, options = gi_of(mode)
                    r = self.master(anim_path, frames, ["--gi", gi, *options, "--no-accumulate"], out, seed)
                except ModeRejected as e:
                    self.skipped[mode] = f"igi-master rejected --gi {mode}: {e}"
                    log(f"SKIPPED mode {mode}: {self.skipped[mode]}")
                    break
                except RuntimeError as e:
                    # The other modes and animations go on; the failure is in the notes.
                    log(f"{name}: {mode}: FAILED: {e}")
                    self.notes.append(f"{name}, `{mode}`, seed {seed}: the session failed: {str(e).splitlines()[0]}")
                    per_seed = []
                    break
                imgs = [read_exr(p, self.scratch) for p in r["images"]]
                errs = self.errors(imgs, [refs[t] for t in range(frames)], r["images"], ref_images)
                flick = {}
                for t, p in pairs.items():
                    if isinstance(p, tuple):
                        mask, denom = p[0], p[1]
                        flick[t] = float(np.abs(imgs[t] - imgs[t - 1]).mean(axis=2)[mask].mean()) / denom
                per_seed.append({"seed": seed, "run": r, "errs": errs, "flicker": flick})
            if mode in self.skipped or not per_seed:
                continue
            n = len(per_seed)
            spf = [s["run"]["seconds"] / frames for s in per_seed]
            self.runs[(name, mode)] = {
                "seeds": [s["seed"] for s in per_seed],
                "spf": statistics.mean(spf), "spf_by_seed": spf,
                "latency": statistics.median(f["seconds"] for s in per_seed for f in s["run"]["frames"]),
                "rays": statistics.mean(f["rays"] for s in per_seed for f in s["run"]["frames"]),
                "shadow_rays_per_pixel": statistics.mean(f["shadow_rays_per_pixel"] for s in per_seed
                                                         for f in s["run"]["frames"]),
                "wall": statistics.mean(s["run"]["wall"] for s in per_seed)}
            for t in range(frames):
                p = pairs.get(t)
                fl = [s["flicker"][t] for s in per_seed if t in s["flicker"]]
                rel = [s["errs"][t]["relative_mse"] for s in per_seed]
                self.rows.append({
                    "animation": name, "mode": mode, "frame": t, "epoch": ref["epochs"][t],
                    "ref_frame": ref["ref_frame"][t], "ref_spp": ref["ref_spp"][t],
                    "ref_floor": ref["floor_relative_mse"] * ref["spp"] / ref["ref_spp"][t],
                    "relmse": statistics.mean(rel),
                    "relmse_sd": statistics.stdev(rel) if n > 1 else 0.0,
                    "bias": statistics.mean(s["errs"][t]["mean_relative_bias"] for s in per_seed),
                    "rmse": statistics.mean(s["errs"][t]["rmse"] for s in per_seed),
                    "flicker": statistics.mean(fl) if fl else None,
                    "ref_flicker": p[2] if isinstance(p, tuple) else None,
                    "mask_fraction": p[3] if isinstance(p, tuple) else None,
                    "pair_skipped": p if isinstance(p, str) else "",
                    "seconds": statistics.mean(s["run"]["frames"][t]["seconds"] for s in per_seed),
                    "rays": statistics.mean(s["run"]["frames"][t]["rays"] for s in per_seed),
                    "shadow_rays_per_pixel": statistics.mean(s["run"]["frames"][t]["shadow_rays_per_pixel"]
                                                             for s in per_seed)})
            # The images of the modes are kept (out/ is not in git); the report needs only rows.
        self.anims[name]["pairs"] = {t: (p if isinstance(p, str) else "ok") for t, p in pairs.items()}

    def run_all(self):
        for name, rel_path, what, divisor in ANIMS:
            if name not in self.a.anims:
                continue
            try:
                self.run_animation(name, rel_path, what, max(1, self.a.ref_spp // divisor))
            except RuntimeError as e:
                log(f"{name}: FAILED: {e}")
                self.notes.append(f"{name}: the run failed: {str(e).splitlines()[0]}")
        shutil.rmtree(self.scratch, ignore_errors=True)


# -------------------------------------------------------------------- analysis
def changes_after_still(epochs):
    """(change frame, first still frame) for each epoch change after >= LAG_MIN_STILL still frames."""
    out, start = [], 0
    for t in range(1, len(epochs)):
        if epochs[t] != epochs[t - 1]:
            if t - start >= LAG_MIN_STILL:
                out.append((t, start))
            start = t
    return out


def analyse(bench):
    summary = {}
    for name in bench.anims:
        if name not in bench.refs:
            continue
        ref = bench.refs[name]
        for mode in bench.a.modes:
            rows = [r for r in bench.rows if r["animation"] == name and r["mode"] == mode]
            if not rows:
                continue
            run = bench.runs[(name, mode)]
            fl = [r["flicker"] for r in rows if r["flicker"] is not None]
            rfl = [r["ref_flicker"] for r in rows if r["ref_flicker"] is not None]
            lags = []
            for change, start in changes_after_still(ref["epochs"]):
                level = statistics.mean(r["relmse"] for r in rows[start:change])
                lag = None
                for r in rows[change:]:
                    if r["relmse"] < LAG_FACTOR * level:
                        lag = r["frame"] - change
                        break
                after = [r["relmse"] for r in rows[change:]]
                lags.append({"change_frame": change, "still_frames": change - start, "still_level": level,
                             "first_error": rows[change]["relmse"], "lag_frames": lag,
                             "after_mean": statistics.mean(after), "after_median": statistics.median(after),
                             "still_median": statistics.median(r["relmse"] for r in rows[start:change]),
                             "frames_after": len(rows) - change,
                             "lag_seconds": None if lag is None else lag * run["spf"]})
            summary.setdefault(name, {})[mode] = {
                "frames": len(rows),
                "relmse": statistics.mean(r["relmse"] for r in rows),
                "relmse_median": statistics.median(r["relmse"] for r in rows),
                "ref_floor": statistics.mean(r["ref_floor"] for r in rows),
                "bias": statistics.mean(r["bias"] for r in rows),
                "abs_bias": statistics.mean(abs(r["bias"]) for r in rows),
                "flicker": statistics.mean(fl) if fl else None,
                "ref_flicker": statistics.mean(rfl) if rfl else None,
                "flicker_pairs": len(fl),
                "mask_fraction": statistics.mean(r["mask_fraction"] for r in rows if r["mask_fraction"] is not None)
                if fl else None,
                "lags": lags,
                "spf": run["spf"], "fps": 1.0 / run["spf"] if run["spf"] > 0 else None, "latency": run["latency"],
                "rays": run["rays"], "shadow_rays_per_pixel": run["shadow_rays_per_pixel"], "seeds": run["seeds"]}
    return summary


def equal_time(summary):
    """Per animation: the modes' seconds per frame against the fastest; a sentence each."""
    out = {}
    for name, modes in summary.items():
        if len(modes) < 2:
            continue
        fastest = min(modes, key=lambda m: modes[m]["spf"])
        slow = [(m, modes[m]["spf"] / modes[fastest]["spf"] - 1) for m in modes if m != fastest]
        over = [(m, x) for m, x in slow if x > EQUAL_TIME_TOLERANCE]
        out[name] = {"fastest": fastest, "slower": {m: x for m, x in slow}, "over": [m for m, _ in over]}
    return out


# -------------------------------------------------------------------- formatting
def pct(x, digits=2, sign=False):
    if x is None:
        return "n/a"
    return f"{100 * x:{'+' if sign else ''}.{digits}f} %"


def lag_text(lags):
    if not lags:
        return "n/a"
    parts = []
    for g in lags:
        if g["lag_frames"] is None:
            parts.append(f"never (in {g['frames_after']} frames)")
        else:
            parts.append(f"{g['lag_frames']} frame{'' if g['lag_frames'] == 1 else 's'} ({g['lag_seconds']:.2g} s)")
    return "; ".join(parts)


def plot_errors(bench, name, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(10, 4.6))
    rows = [r for r in bench.rows if r["animation"] == name]
    for mode in bench.a.modes:
        pts = [r for r in rows if r["mode"] == mode]
        if pts:
            ax.plot([r["frame"] for r in pts], [r["relmse"] for r in pts], marker="o", markersize=3, label=mode)
    modes = [m for m in bench.a.modes if any(r["mode"] == m for r in rows)]
    if modes:
        pts = [r for r in rows if r["mode"] == modes[0]]
        ax.plot([r["frame"] for r in pts], [r["ref_floor"] for r in pts], "k:", lw=1,
                label="reference's own noise (estimate)")
    for change, _ in changes_after_still(bench.refs[name]["epochs"]):
        ax.axvline(change, color="k", lw=0.8, ls="--", alpha=0.6)
        ax.annotate("change", (change, 1), xycoords=("data", "axes fraction"), xytext=(3, -12),
                    textcoords="offset points", fontsize=8)
    ax.set_yscale("log")
    ax.set_xlim(-0.5, bench.anims[name]["frames"] - 0.5)
    ax.xaxis.get_major_locator().set_params(integer=True)
    ax.set_xlabel("frame")
    ax.set_ylabel("relMSE against the frame's path-traced reference (log)")
    a = bench.a
    ax.set_title(f"{name}: each frame alone (--no-accumulate), {a.width}x{a.height}, "
                 f"mean over seeds {','.join(map(str, a.seeds))}")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_flicker(bench, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = [n for n in bench.anims if n in bench.refs]
    fig, axes = plt.subplots(len(names), 1, figsize=(10, 2.8 * len(names) + 0.6), squeeze=False)
    for ax, name in zip(axes[:, 0], names):
        rows = [r for r in bench.rows if r["animation"] == name]
        first = None
        for mode in bench.a.modes:
            pts = [r for r in rows if r["mode"] == mode]
            if not pts:
                continue
            first = first or pts
            ax.plot([r["frame"] for r in pts], [100 * r["flicker"] if r["flicker"] is not None else float("nan")
                                                for r in pts], marker="o", markersize=3, label=mode)
        if first:
            ax.plot([r["frame"] for r in first], [100 * r["ref_flicker"] if r["ref_flicker"] is not None
                                                  else float("nan") for r in first], "k:", lw=1,
                    label="reference against its previous frame")
        ax.set_title(f"{name}: mean |frame t - frame t-1| over the static mask / mean reference there", fontsize=9)
        ax.set_ylabel("flicker, %")
        ax.set_xlim(-0.5, bench.anims[name]["frames"] - 0.5)
        ax.xaxis.get_major_locator().set_params(integer=True)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    axes[-1, 0].set_xlabel("frame t (gaps: the camera moved, or no static pixels)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def papers_table(summary):
    lines = ["| work | mode | hardware | scene, size | speed | lag after a change | flicker | image error |",
             "|---|---|---|---|---|---|---|---|"]
    for p in PAPERS:
        lines.append(f"| {p['paper']} | `{p['mode']}` | {p['hardware']} | {p['setting']} | {p['speed']} | {p['lag']} | "
                     f"{p['flicker']} | {p['error']} |")
    return "\n".join(lines)


def ours_rows(bench, summary):
    """One line per mode with our figures over the animations, for the papers' table."""
    a = bench.a
    m = machine()
    lines = []
    for mode in a.modes:
        per = {name: s[mode] for name, s in summary.items() if mode in s}
        if not per:
            why = bench.skipped.get(mode, "not run")
            lines.append(f"| this cluster (run above) | `{mode}` | - | - | not measured: {why} | | | |")
            continue
        spf = " / ".join(f"{name} {1 / v['spf']:.3g} fps" for name, v in per.items())
        lag = "; ".join(f"{name}: {lag_text(v['lags'])}" for name, v in per.items() if v["lags"]) or "n/a"
        fl = " / ".join(f"{name} {pct(v['flicker'])}" for name, v in per.items() if v["flicker"] is not None) or "n/a"
        err = " / ".join(f"{name} {num(v['relmse'])}" for name, v in per.items())
        lines.append(f"| this cluster (run above) | `{mode}` | {a.clients} local client, {m['nproc']} shared cores "
                     f"({m['cpu']}) | Cornell box (scenes/cornell), {a.width} x {a.height}, --no-accumulate | {spf} | "
                     f"{lag} | {fl} | relMSE {err} |")
    return "\n".join(lines)


def write_reports(bench, docs, command, started, doc_prefix):
    a = bench.a
    os.makedirs(docs, exist_ok=True)
    summary = analyse(bench)
    eq = equal_time(summary)
    fields = ["animation", "mode", "frame", "epoch", "ref_frame", "ref_spp", "ref_floor", "relmse", "relmse_sd",
              "bias", "rmse", "flicker", "ref_flicker", "mask_fraction", "pair_skipped", "seconds", "rays",
              "shadow_rays_per_pixel"]
    with open(os.path.join(docs, "results.csv"), "w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        for r in bench.rows:
            w.writerow({k: ("" if r[k] is None else r[k]) for k in fields})
    end = machine()
    seeds = ",".join(map(str, a.seeds))
    lines = [
        f"- command: `{command}`",
        f"- machine: {end['uname']}, {end['nproc']} cores ({end['cpu']}); started {started['date']} "
        f"(load average {started['load']}), finished {end['date']} (load {end['load']}); the two cores are "
        "shared with other work, so timings carry that noise",
        f"- build: `{a.build}`; {a.width} x {a.height}, {a.clients} local client(s), scene `{os.path.relpath(a.scene, ROOT)}`; "
        f"every mode with `--no-accumulate`, seeds {seeds} (figures are means over the seeds)",
    ]
    if a.quick:
        lines.append("- **smoke run** (--quick): few frames, a weak reference; not evidence")
    for mode, why in bench.skipped.items():
        lines.append(f"- mode `{mode}` skipped: {why}")
    for n in bench.notes:
        lines.append(f"- {n}")
    setup = "\n".join(lines)

    refs = ["| animation | frames | what moves | reference | its time | its noise (relMSE at its spp) |",
            "|---|---|---|---|---|---|"]
    for name, info in bench.anims.items():
        ref = bench.refs.get(name)
        if not ref:
            refs.append(f"| {name} | {info['frames']} | {info['what']} | failed | | |")
            continue
        longest = max(ref["ref_spp"])
        spp = f"{ref['spp']} spp per frame" + (f" (still epochs accumulated: up to {longest} spp)" if longest > ref["spp"] else "")
        cut = f" of {info['length']}" if info["frames"] < info["length"] else ""
        refs.append(f"| {name} (`{info['file']}`) | {info['frames']}{cut} | {info['what']} | path tracer, {spp} | "
                    f"{ref['seconds_per_frame']:.2f} s/frame{' (cached)' if ref.get('cached') else ''} | "
                    f"{num(ref['floor_relative_mse'])} |")

    res = ["| animation | mode | relMSE mean (median) | reference noise in it | bias | flicker (reference's own) | "
           "pairs with a static mask (mean share of pixels) | lag after the change | s/frame (fps) | "
           "latency of a frame | rays/frame | shadow rays/px |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for name, modes in summary.items():
        for mode, s in modes.items():
            res.append(f"| {name} | `{mode}` | {num(s['relmse'])} ({num(s['relmse_median'])}) | {num(s['ref_floor'])} | "
                       f"{pct(s['bias'], sign=True)} | {pct(s['flicker'])} ({pct(s['ref_flicker'])}) | "
                       f"{s['flicker_pairs']} ({pct(s['mask_fraction'], 0)}) | {lag_text(s['lags'])} | "
                       f"{s['spf']:.3g} ({s['fps']:.3g}) | {s['latency'] * 1e3:.0f} ms | {s['rays'] / 1e6:.3g} M | "
                       f"{s['shadow_rays_per_pixel']:.3g} |")
    lagd = []
    for name, modes in summary.items():
        for mode, s in modes.items():
            for g in s["lags"]:
                lagd.append(f"- {name}, `{mode}`: change at frame {g['change_frame']} after {g['still_frames']} still "
                            f"frames; still level relMSE {num(g['still_level'])}, first frame after it "
                            f"{num(g['first_error'])} ({g['first_error'] / g['still_level']:.2g} x); back under "
                            f"{LAG_FACTOR} x: {lag_text([g])}; the {g['frames_after']} frames from the change on: "
                            f"mean {num(g['after_mean'])} ({g['after_mean'] / g['still_level']:.2g} x the still level), "
                            f"median {num(g['after_median'])} (still frames' median {num(g['still_median'])})")
    eqt = []
    for name, e in eq.items():
        spf = ", ".join(f"`{m}` {summary[name][m]['spf']:.3g} s" for m in summary[name])
        if e["over"]:
            slower = ", ".join(f"`{m}` {100 * e['slower'][m]:.0f} % slower" for m in e["over"])
            eqt.append(f"- {name}: seconds per frame {spf}: **not at equal time**: against `{e['fastest']}`, {slower} "
                       f"(more than {100 * EQUAL_TIME_TOLERANCE:.0f} %)")
        else:
            eqt.append(f"- {name}: seconds per frame {spf}: within {100 * EQUAL_TIME_TOLERANCE:.0f} % of each other")
    plots = []
    for name in summary:
        png = f"{name}.png"
        plot_errors(bench, name, os.path.join(docs, png))
        plots.append(f"![{name}: relMSE per frame and mode]({doc_prefix}{png})")
    if summary:
        plot_flicker(bench, os.path.join(docs, "flicker.png"))
        plots.append(f"![flicker per pair of frames and mode]({doc_prefix}flicker.png)")

    method = (
        f"Each frame of each mode is compared (relMSE, mean bias) with a path-traced reference of "
        f"that frame's scene state at the same {a.width} x {a.height}: our path tracer on the same animation, "
        f"{a.ref_spp} spp per frame ({max(1, a.ref_spp // 4)} for `jump`, whose still epochs accumulate 8 and more "
        "frames), accumulated while the scene holds still (a frame's reference is the last image of its epoch), "
        f"cached in `{os.path.relpath(a.ref_dir, ROOT)}/`. relMSE = mean over pixels and channels of "
        "(image - reference)^2 / (reference^2 + 0.01), bias = sum(image) / sum(reference) - 1, as `igi-compare` "
        "computes them (checked against it on the first and last frame of every session). The reference's own "
        "noise (half the relMSE between two seeds of frame 0, divided by the frames its epoch accumulated) is in "
        "the error too. "
        f"Flicker: over pairs of consecutive frames whose camera did not move, the pixels whose references "
        f"(3 x 3 blurred luminance) agree within {100 * MASK_REL:.0f} % plus {100 * MASK_ABS:.1f} % of the image's "
        f"mean and stay at or below {MASK_WHITE:g} (white on screen: the light and its reflections are left out); mean |frame t - frame t-1| there over the mean reference there (pairs under "
        f"{100 * MASK_MIN_FRACTION:.0f} % of the pixels skipped, and pairs whose static pixels are darker than "
        f"{100 * DARK_FRACTION:.0f} % of the animation's mean reference: the light off). Lag: after a change that follows at least "
        f"{LAG_MIN_STILL} still frames, the frames until the relMSE is under {LAG_FACTOR} x the mode's mean over "
        "those still frames. Seconds per frame: the session's render time over its frames (throughput, "
        "`--stats-json`); rays per frame: the clients' count (eye, shadow and light-set rays).")
    body = "\n\n".join([
        setup,
        "#### Method\n\n" + method,
        "#### Animations and references\n\n" + "\n".join(refs),
        "#### Results\n\n" + "\n".join(res),
        "#### At equal time per frame?\n\n" + ("\n".join(eqt) if eqt else "- one mode only"),
        "#### Lag\n\n" + ("\n".join(lagd) if lagd else "- no change after a still scene was measured"),
        "#### Plots\n\n" + "\n\n".join(plots),
        "#### The papers' own claims beside ours\n\n" + papers_table(summary) + "\n" + ours_rows(bench, summary),
    ])
    with open(os.path.join(docs, "results.md"), "w", encoding="utf-8") as f:
        f.write("# GI modes: measurements\n\n" + body.replace(f"]({doc_prefix}", "](") + "\n")
    with open(os.path.join(docs, "summary.json"), "w", encoding="utf-8") as f:
        json.dump({"command": command, "machine_start": started, "machine_end": end, "quick": a.quick,
                   "settings": {"width": a.width, "height": a.height, "clients": a.clients, "seeds": a.seeds,
                                "ref_spp": a.ref_spp, "modes": a.modes, "max_frames": a.max_frames,
                                "build": a.build, "mask_rel": MASK_REL, "mask_abs": MASK_ABS,
                                "lag_factor": LAG_FACTOR},
                   "animations": bench.anims, "references": bench.refs, "skipped": bench.skipped,
                   "notes": bench.notes, "summary": summary, "equal_time": eq, "papers": PAPERS},
                  f, indent=1, default=str)
    return {"modes": body}, summary, eq


def print_summary(bench, summary, eq, docs):
    print("", flush=True)
    print("=" * 112)
    print("GI modes, each frame alone" + (" (SMOKE RUN: --quick; not evidence)" if bench.a.quick else ""))
    print("=" * 112)
    print(f"{'animation':<13} {'mode':<7} {'relMSE':>8} {'median':>8} {'ref noise':>9} {'bias':>8} {'flicker':>8} "
          f"{'ref flk':>8} {'lag':<22} {'s/frame':>8} {'Mrays/frame':>11}")
    for name, modes in summary.items():
        for mode, s in modes.items():
            print(f"{name:<13} {mode:<7} {num(s['relmse']):>8} {num(s['relmse_median']):>8} {num(s['ref_floor']):>9} "
                  f"{pct(s['bias'], 1, True):>8} "
                  f"{pct(s['flicker']):>8} {pct(s['ref_flicker']):>8} {lag_text(s['lags']):<22} {s['spf']:>8.3g} "
                  f"{s['rays'] / 1e6:>11.3g}")
    for name, e in eq.items():
        if e["over"]:
            print(f"{name}: NOT at equal time per frame: " +
                  ", ".join(f"{m} {100 * e['slower'][m]:.0f} % slower than {e['fastest']}" for m in e["over"]))
    for mode, why in bench.skipped.items():
        print(f"mode {mode} SKIPPED: {why}")
    for n in bench.notes:
        print(f"note: {n}")
    print("-" * 112)
    print(f"report in {docs}")
    sys.stdout.flush()


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--build", default=os.path.join(ROOT, "build"), help="build folder (its bin/ has igi-master)")
    p.add_argument("--out", default=None, help="images and runs (default out/modes; with --quick out/modes-quick)")
    p.add_argument("--ref-dir", default=None, help="cached references (default OUT/reference)")
    p.add_argument("--docs", default=None,
                   help="tables and plots (default docs/modes; with --quick, or '', OUT/report and no document)")
    p.add_argument("--doc", default=os.path.join(ROOT, "docs", "MODES.md"), help="document whose generated block is replaced")
    p.add_argument("--quick", action="store_true", help="smoke run: 20 frames per animation, 128-spp reference, one seed")
    p.add_argument("--modes", default=DEFAULT_MODES, help=f"comma-separated GI modes (default {DEFAULT_MODES})")
    p.add_argument("--anims", default=",".join(ANIM_NAMES), help="comma-separated subset of: " + ", ".join(ANIM_NAMES))
    p.add_argument("--scene", default=SCENE, help="the scene the animations are for")
    p.add_argument("--width", type=int, default=160)
    p.add_argument("--height", type=int, default=120)
    p.add_argument("--clients", type=int, default=1, help="local clients")
    p.add_argument("--ref-spp", type=int, default=None, help="reference spp per frame (default 1024; --quick 128)")
    p.add_argument("--seeds", default=None, help="seeds of the mode sessions (default 1,2,3; --quick 1)")
    p.add_argument("--max-frames", type=int, default=None,
                   help="at most this many frames of each animation (default all; --quick 20)")
    p.add_argument("--command", default="scripts/bench_modes.sh", help="the command line recorded in the document")
    a = p.parse_args()
    a.modes = [m for m in a.modes.split(",") if m]
    a.anims = [x for x in a.anims.split(",") if x]
    unknown = [x for x in a.anims if x not in ANIM_NAMES]
    if unknown:
        p.error(f"unknown animation(s) {', '.join(unknown)}; known: {', '.join(ANIM_NAMES)}")
    if not a.modes:
        p.error("--modes is empty")
    defaults = ({"ref_spp": 128, "seeds": "1", "max_frames": 20} if a.quick
                else {"ref_spp": 1024, "seeds": "1,2,3", "max_frames": 0})
    for key, value in defaults.items():
        if getattr(a, key) is None:
            setattr(a, key, value)
    try:
        a.seeds = [int(x) for x in str(a.seeds).split(",") if x]
    except ValueError:
        p.error(f"--seeds: integers separated by commas, got {a.seeds!r}")
    if not a.seeds:
        p.error("--seeds is empty")
    a.build = os.path.abspath(a.build)
    a.scene = os.path.abspath(a.scene)
    if a.out is None:
        a.out = os.path.join(ROOT, "out", "modes-quick" if a.quick else "modes")
    a.out = os.path.abspath(a.out)
    a.ref_dir = os.path.abspath(a.ref_dir or os.path.join(a.out, "reference"))
    if a.docs is None:
        a.docs = "" if a.quick else os.path.join(ROOT, "docs", "modes")
    for tool in ("oiiotool",):
        if not shutil.which(tool):
            log(f"note: {tool} not found (only needed for EXR files igi-master does not write)")
    started = machine()
    bench = Bench(a)
    bench.run_all()
    if not bench.rows:
        for mode, why in bench.skipped.items():
            log(f"mode {mode} skipped: {why}")
        raise SystemExit("nothing was measured")
    docs = a.docs if a.docs else os.path.join(a.out, "report")
    # Image links: relative to docs/MODES.md when the report is docs/modes/, else to results.md.
    doc_prefix = os.path.relpath(docs, os.path.dirname(os.path.abspath(a.doc))) + "/" if a.docs else ""
    parts, summary, eq = write_reports(bench, docs, a.command, started, doc_prefix)
    if a.docs and not a.quick:
        report_util.splice(a.doc, parts, log)
        log(f"replaced the GENERATED modes block of {a.doc}")
    log(f"wrote {docs}/results.md, results.csv, summary.json and plots")
    print_summary(bench, summary, eq, docs)


if __name__ == "__main__":
    main()
