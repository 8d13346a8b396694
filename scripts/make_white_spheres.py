#!/usr/bin/env python3
"""Writes scenes/materials/white-spheres.gltf: two white dielectric spheres (glTF
metallic-roughness: base colour 0.8, metallic 0, roughness 0.35 on the left and 1 on the right),
radius 0.35, on the floor of the Cornell room (scenes/materials/burley-spheres.json). The scene
that isolates the Principled BSDF's Burley diffuse against Lambert: scripts/materials_mustshow.py
renders it with Cycles twice, as imported and with each Principled's diffuse swapped for a
Lambertian Diffuse BSDF (scripts/peers/cycles_render.py, IGI_CYCLES_DIFFUSE=lambert).

Usage: scripts/make_white_spheres.py [OUT]   (default: scenes/materials/white-spheres.gltf)
"""
import base64
import json
import math
import os
import struct
import sys

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "scenes", "materials", "white-spheres.gltf")
RINGS, SEGMENTS, RADIUS = 32, 64, 0.35


def uv_sphere():
    pos, nrm, idx = [], [], []
    for i in range(RINGS + 1):
        theta = math.pi * i / RINGS
        for j in range(SEGMENTS + 1):
            phi = 2 * math.pi * j / SEGMENTS
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))
            nrm.append(n)
            pos.append(tuple(RADIUS * c for c in n))
    for i in range(RINGS):
        for j in range(SEGMENTS):
            a, b = i * (SEGMENTS + 1) + j, (i + 1) * (SEGMENTS + 1) + j
            if i > 0:
                idx.append((a, b, a + 1))
            if i < RINGS - 1:
                idx.append((a + 1, b, b + 1))
    return pos, nrm, idx


pos, nrm, idx = uv_sphere()
blob = b"".join(struct.pack("<3f", *p) for p in pos) + b"".join(struct.pack("<3f", *n) for n in nrm)
index_offset = len(blob)
blob += b"".join(struct.pack("<3I", *t) for t in idx)
n_vert = len(pos)
gltf = {
    "asset": {"version": "2.0", "generator": "scripts/make_white_spheres.py"},
    "scene": 0,
    "scenes": [{"nodes": [0, 1]}],
    "nodes": [{"mesh": 0, "translation": [-0.45, RADIUS, 0.0]}, {"mesh": 1, "translation": [0.45, RADIUS, 0.0]}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": m}]}
               for m in (0, 1)],
    "materials": [{"name": f"white_roughness_{r}",
                   "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1.0], "metallicFactor": 0.0,
                                            "roughnessFactor": r}} for r in (0.35, 1.0)],
    "buffers": [{"byteLength": len(blob),
                 "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 12 * n_vert, "target": 34962},
                    {"buffer": 0, "byteOffset": 12 * n_vert, "byteLength": 12 * n_vert, "target": 34962},
                    {"buffer": 0, "byteOffset": index_offset, "byteLength": 12 * len(idx), "target": 34963}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": n_vert, "type": "VEC3",
                   "min": [-RADIUS] * 3, "max": [RADIUS] * 3},
                  {"bufferView": 1, "componentType": 5126, "count": n_vert, "type": "VEC3"},
                  {"bufferView": 2, "componentType": 5125, "count": 3 * len(idx), "type": "SCALAR"}],
}
with open(out, "w") as f:
    json.dump(gltf, f)
print(f"wrote {out}: {n_vert} vertices, {len(idx)} triangles per sphere")
