#!/usr/bin/env python3
"""Writes scenes/gltf_lights/: glTF files that hold one KHR_lights_punctual light each (a point
light, a spot light and a directional light, in the specification's candela and lux) and a scene
file per light that puts it over a diffuse floor (an OBJ, so that Cycles gets the same Lambert
surface rather than the Principled BSDF's Burley diffuse). scripts/gltf_light_units.sh renders
them with igi and with Cycles through Blender's own glTF importer: the images agree only if both
convert the photometric units the same way (docs/SCENE_FORMAT.md, "glTF").

Usage: scripts/make_gltf_lights_scene.py [OUT_DIR]   (default: scenes/gltf_lights)
"""
import json
import math
import os
import sys

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "scenes", "gltf_lights")
os.makedirs(out, exist_ok=True)


def about_x(deg):
    """The glTF quaternion (x, y, z, w) of a turn of `deg` degrees about +X."""
    h = math.radians(deg) / 2
    return [math.sin(h), 0.0, 0.0, math.cos(h)]


# A light shines along its node's -Z: a turn of -90 degrees about X points it straight down,
# one of -60 degrees down and towards -Z.
LIGHTS = {
    "point": ({"type": "point", "intensity": 400.0, "color": [1.0, 0.85, 0.7]},
              {"translation": [0.3, 1.4, 0.2]}),
    # The floor the camera sees lies well inside the inner cone: the units are compared, not
    # the ramps (Blender's spot blend is its own, docs/LIGHTS.md, "Spot lights").
    "spot": ({"type": "spot", "intensity": 600.0, "color": [0.8, 0.9, 1.0],
              "spot": {"innerConeAngle": 1.2, "outerConeAngle": 1.3}},
             {"translation": [0.0, 1.6, 0.0], "rotation": about_x(-90)}),
    "sun": ({"type": "directional", "intensity": 300.0, "color": [1.0, 0.95, 0.9]},
            {"rotation": about_x(-60)}),
}

for name, (light, node) in LIGHTS.items():
    light = dict(light, name=name)
    gltf = {
        "asset": {"version": "2.0", "generator": "scripts/make_gltf_lights_scene.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [light]}},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [dict(node, name=name, extensions={"KHR_lights_punctual": {"light": 0}})],
    }
    with open(os.path.join(out, name + ".gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")
    # Cycles (Blender 3.4) weighs a spot light by the cosine to its axis on top of the blend
    # (kernel spot_light_attenuation); glTF has no such factor. The spot's camera looks
    # straight down at the floor under it, narrowly, where that cosine is above 0.99.
    camera = ({"position": [0, 3, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "fov_y": 6}
              if name == "spot" else
              {"position": [0, 1.2, 2.6], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov_y": 40})
    scene = {
        "camera": camera,
        "image": {"width": 160, "height": 120, "exposure": 0},
        "meshes": [{"file": "floor.obj", "name": "floor"},
                   {"file": name + ".gltf", "name": name + "_light"}],
        "render": {"caustic_photons": 0},
    }
    with open(os.path.join(out, name + ".json"), "w") as f:
        json.dump(scene, f, indent=1)
        f.write("\n")

with open(os.path.join(out, "floor.obj"), "w") as f:
    f.write("# A 6 x 6 floor at y = 0, facing +y (default material: diffuse).\n"
            "v -3 0 -3\nv 3 0 -3\nv 3 0 3\nv -3 0 3\nvn 0 1 0\n"
            "f 1//1 4//1 3//1\nf 1//1 3//1 2//1\n")
print("wrote", out)
