"""Where a sun's light paths go in a scene: how many of their first vertices (VPLs) can light
anything the camera sees. Geometry only; the renderer is not involved (and not changed).

Usage:
  blender -b --factory-startup -noaudio -P scripts/peers/sun_paths.py -- SCENE [PATHS] [RECEIVERS]

The light paths start as the renderer starts a directional light's (docs/LIGHTS.md,
Lights::parallelStart): uniformly on the rectangle across the light that the scene's bounding
box fills (its eight corners' extent on the two axes of the renderer's Frame about the
direction), or on the disk of the bounding sphere when that is smaller, travelling along the
light's direction (its centre direction: the sun's 0.53-degree disk is ignored). Each path's first hit is its first VPL. The camera's receivers are the first
hits of RECEIVERS (default 400) camera rays through random pixels. A VPL is *useful* when at
least one receiver lies in front of it, faces it and sees it (a shadow ray); otherwise it is
*wasted*: no pixel's first hit can receive its light directly (it may still light others
through further bounces: its path continues). Prints JSON: paths, missed (hit nothing), first
vertex wasted, useful, and the same over the second vertices (a cosine-distributed bounce from
each first vertex, whatever its colour) as a hint of what the path's continuation reaches.

Runs in Blender's Python for mathutils' BVH (Embree is not reachable from Python here).
"""

import json
import math
import os
import random
import sys

import mathutils
from mathutils.bvhtree import BVHTree

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import igi_scene  # noqa: E402


def frame(n):
    """The renderer's Frame (math/Frame.h, Duff et al. 2017): the axes s, t across n."""
    sign = math.copysign(1.0, n.z)
    a = -1.0 / (sign + n.z)
    b = n.x * n.y * a
    return (mathutils.Vector((1 + sign * n.x * n.x * a, sign * b, -sign * n.x)),
            mathutils.Vector((b, sign + n.y * n.y * a, -n.y)))


def start_area(lo, hi, centre, radius, d):
    """Where the renderer starts a parallel light's paths along d: a function of two uniform
    numbers to a point, as Lights::parallelStart does (the box's rectangle, or the disk)."""
    s, t = frame(d)
    corners = [mathutils.Vector((hi.x if c & 1 else lo.x, hi.y if c & 2 else lo.y,
                                 hi.z if c & 4 else lo.z)) - centre for c in range(8)]
    xs, ys = [c.dot(s) for c in corners], [c.dot(t) for c in corners]
    area = (max(xs) - min(xs)) * (max(ys) - min(ys))
    back = centre - d * (radius * 1.001)
    if 0 < area < math.pi * radius * radius:
        return lambda a, b: (back + s * (min(xs) + a * (max(xs) - min(xs)))
                             + t * (min(ys) + b * (max(ys) - min(ys))))
    u, v = basis(d)

    def disk(a, b):
        r, phi = radius * math.sqrt(a), 2 * math.pi * b
        return back + u * (r * math.cos(phi)) + v * (r * math.sin(phi))
    return disk


def basis(n):
    a = mathutils.Vector((1, 0, 0)) if abs(n.x) < 0.9 else mathutils.Vector((0, 1, 0))
    u = n.cross(a).normalized()
    return u, n.cross(u)


def main(argv):
    scene_path = argv[0]
    n_paths = int(argv[1]) if len(argv) > 1 else 4000
    n_recv = int(argv[2]) if len(argv) > 2 else 400
    rng = random.Random(1)
    flat = igi_scene.flatten(scene_path, punctual_lights=True)
    verts, polys = [], []
    for m in flat["meshes"]:
        base = len(verts)
        verts += [tuple(p) for p in m["positions"]]
        polys += [tuple(base + i for i in t) for t in m["triangles"]]
    bvh = BVHTree.FromPolygons(verts, polys, all_triangles=True, epsilon=0.0)
    lo, hi = (mathutils.Vector(b) for b in flat["bounds"])
    centre, radius = (lo + hi) / 2, (hi - lo).length / 2
    eps = 1e-4 * radius

    cam = flat["camera"]
    eye = mathutils.Vector(cam["position"])
    fwd = (mathutils.Vector(cam["look_at"]) - eye).normalized()
    right = fwd.cross(mathutils.Vector(cam["up"])).normalized()
    up = right.cross(fwd)
    th = math.tan(math.radians(cam["fov_y"]) / 2)
    aspect = flat["width"] / flat["height"]
    receivers = []
    while len(receivers) < n_recv:
        x, y = (2 * rng.random() - 1) * th * aspect, (2 * rng.random() - 1) * th
        d = (fwd + right * x + up * y).normalized()
        loc, nrm, _, _ = bvh.ray_cast(eye, d)
        if loc is None:
            receivers.append(None)  # the sky: counted, receives nothing
            continue
        if nrm.dot(d) > 0:
            nrm = -nrm
        receivers.append((loc + nrm * eps, nrm))
    seen_points = [r for r in receivers if r]

    def useful(p, n):
        """Can the VPL at p (normal n, facing where its light came from) light a receiver?"""
        for q, m in seen_points:
            w = q - p
            dist = w.length
            if dist <= 0:
                continue
            w /= dist
            if n.dot(w) <= 0 or m.dot(-w) <= 0:
                continue
            hit = bvh.ray_cast(p, w, dist * (1 - 1e-4))
            if hit[0] is None:
                return True
        return False

    suns = [l for l in flat["punctual_lights"] if l["type"] == "directional"]
    if not suns:
        raise SystemExit(f"{scene_path}: no directional light")
    out = {"scene": scene_path, "paths": n_paths, "receivers": n_recv,
           "receivers_on_geometry": len(seen_points), "suns": []}
    for sun in suns:
        d = mathutils.Vector(sun["direction"]).normalized()
        start = start_area(lo, hi, centre, radius, d)
        counts = {"missed": 0, "first_wasted": 0, "first_useful": 0,
                  "second_missed": 0, "second_wasted": 0, "second_useful": 0}
        k = int(math.sqrt(n_paths))
        for i in range(n_paths):
            # Stratified on the unit square, then the rectangle (or the disk).
            a, b = ((i % k) + rng.random()) / k, ((i // k % k) + rng.random()) / k
            o = start(a, b)
            loc, nrm, _, _ = bvh.ray_cast(o, d)
            if loc is None:
                counts["missed"] += 1
                continue
            if nrm.dot(d) > 0:
                nrm = -nrm
            p = loc + nrm * eps
            counts["first_useful" if useful(p, nrm) else "first_wasted"] += 1
            # One cosine-distributed bounce.
            t1, t2 = basis(nrm)
            s1, s2 = rng.random(), rng.random()
            rr, ph = math.sqrt(s1), 2 * math.pi * s2
            w = (t1 * (rr * math.cos(ph)) + t2 * (rr * math.sin(ph)) + nrm * math.sqrt(max(0.0, 1 - s1))).normalized()
            loc2, n2, _, _ = bvh.ray_cast(p, w)
            if loc2 is None:
                counts["second_missed"] += 1
                continue
            if n2.dot(w) > 0:
                n2 = -n2
            counts["second_useful" if useful(loc2 + n2 * eps, n2) else "second_wasted"] += 1
        out["suns"].append({"name": sun["name"], "direction": list(d), **counts})
    print("SUNPATHS " + json.dumps(out), flush=True)


if __name__ == "__main__":
    main(sys.argv[sys.argv.index("--") + 1:])
