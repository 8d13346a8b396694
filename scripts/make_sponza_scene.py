#!/usr/bin/env python3
"""Writes the many-lights scene in the Sponza atrium (scenes/sponza/arcades.json).

Dabrovic's Sponza (../shared/scenes/sponza-dabrovic, 66,450 triangles; CC BY-NC, read from
there, never copied) with the Stanford bunny (../shared/scenes/stanford-bunny, 144,046
triangles) standing in the atrium: 210,496 triangles. It is lit only by 120 small square lights
(0.3 m on a side, facing down) hung under the vaults of the arcades: on each of the three
floors, along both long sides, two rows of ten. The open atrium gets light only from the
arcades around it, and each arcade bay mostly from its own lights: the scene that issue 17
asks for, where light samples and VPLs drawn by power go mostly to lights and VPLs far from
the point they light.

Run it only to regenerate the committed file; the build does not need Python.
"""
import json
import os

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes", "sponza")
SHARED = "../../../shared/scenes"

SIDE = 0.3  # a light's edge, metres
RADIANCE = [90.0, 78.0, 60.0]  # warm white; the image averages about 0.4 at exposure 0
XS = [-13.5 + 3.0 * i for i in range(10)]  # bays along the hall
ROWS_Z = [4.6, 6.6]  # two rows under each side's vaults (and their mirror images, -z)
# Just under the lowest point of each floor's vaults (probed: 3.78, 9.21 and 15.1 m).
FLOOR_Y = {"ground": 3.55, "first": 8.95, "second": 14.6}


def lights():
    out = []
    for floor, y in FLOOR_Y.items():
        for side, sign in (("north", 1.0), ("south", -1.0)):
            for row, z in enumerate(ROWS_Z):
                for bay, x in enumerate(XS):
                    # corner + s edge1 + t edge2 faces cross(edge1, edge2): down (-y) with edge1
                    # along +z and edge2 along +x.
                    out.append({
                        "type": "quad",
                        "name": f"{floor}-{side}-{row}-{bay}",
                        "corner": [round(x - SIDE / 2, 4), y, round(sign * z - SIDE / 2, 4)],
                        "edge1": [0, 0, SIDE],
                        "edge2": [SIDE, 0, 0],
                        "radiance": RADIANCE,
                    })
    return out


def main():
    scene = {
        "camera": {"position": [-15.5, 1.7, 1.2], "look_at": [6.0, 5.2, -0.6], "up": [0, 1, 0],
                   "fov_y": 62},
        "image": {"width": 320, "height": 240, "exposure": 0},
        "meshes": [
            {"file": f"{SHARED}/sponza-dabrovic/sponza.obj", "name": "sponza"},
            {"file": f"{SHARED}/stanford-bunny/bunny.obj", "name": "bunny",
             "transform": {"translate": [-3.0, 0.03, 0.4], "rotate_deg": [0, 30, 0],
                           "scale": 1.2}},
        ],
        "lights": lights(),
    }
    os.makedirs(HERE, exist_ok=True)
    # One line per section entry: a diff of a regenerated file stays readable.
    compact = lambda v: json.dumps(v, separators=(", ", ": "))
    lines = ["{"]
    lines.append(f' "camera": {compact(scene["camera"])},')
    lines.append(f' "image": {compact(scene["image"])},')
    lines.append(' "meshes": [')
    lines.append(",\n".join("  " + compact(m) for m in scene["meshes"]))
    lines.append(" ],")
    lines.append(' "lights": [')
    lines.append(",\n".join("  " + compact(l) for l in scene["lights"]))
    lines.append(" ]")
    lines.append("}")
    with open(os.path.join(HERE, "arcades.json"), "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
