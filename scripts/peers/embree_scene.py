"""Writes an igi scene as an Embree tutorial XML scene, for Embree's `pathtracer` (embree-tools).

Usage: python3 embree_scene.py scene.json|model.obj out.xml [light_scale]

Prints the pathtracer's camera options (--vp --vi --vu --fov) on stdout.

Mapping (what matches and what does not):
  diffuse -> "Matte" (Lambertian), mirror -> "Mirror" (perfect mirror; a small diffuse part, as
  the Sphere box's 0.01, is dropped), glass -> "Dielectric" (solid, etaInside = ior),
  glossy -> "OBJ" (Embree's own Phong-like lobe: not the same lobe as ours).
  Emitters (our quad lights and emissive OBJ triangles) -> "QuadLight"/"TriangleLight". The
  pathtracer tutorial adds light only by next-event estimation and on rays that leave the scene,
  so inside a closed room an emitter is never *seen* (camera rays and rays reflected in mirrors
  or refracted by glass find the geometry behind it), and caustics are missing. The emitting
  triangles are removed from the geometry so that they do not cast shadows of their own.
  `light_scale` multiplies every emitter: the tutorial writes 8-bit images clamped to [0, 1],
  so the caller dims the lights and multiplies the image back (linearity of light transport).
"""

import os
import sys

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import igi_scene  # noqa: E402


def _floats(values):
    return " ".join(f"{v:.7g}" for v in values)


def _space(origin, vx, vy):
    """AffineSpace body, rows of (vx vy vz p), vz unused."""
    vz = [0.0, 0.0, 0.0]
    rows = [[vx[i], vy[i], vz[i], origin[i]] for i in range(3)]
    return " ".join(_floats(r) for r in rows)


def _material_xml(mat):
    if mat["type"] == "mirror":
        return '<code>"Mirror"</code><parameters><float3 name="reflectance">%s</float3></parameters>' % _floats(mat["specular"])
    if mat["type"] == "glass":
        return ('<code>"Dielectric"</code><parameters><float name="etaOutside">1</float>'
                '<float name="etaInside">%g</float></parameters>' % mat["ior"])
    if mat["type"] == "glossy":
        return ('<code>"OBJ"</code><parameters><float3 name="Kd">%s</float3><float3 name="Ks">%s</float3>'
                '<float name="Ns">%g</float></parameters>' % (_floats(mat["diffuse"]), _floats(mat["specular"]),
                                                             mat.get("phong_exponent", 10.0)))
    return '<code>"Matte"</code><parameters><float3 name="reflectance">%s</float3></parameters>' % _floats(mat["diffuse"])


def write(scene, out_path, light_scale=1.0):
    parts = ["<?xml version=\"1.0\"?>", "<scene>"]
    for q in scene["quad_lights"]:
        # Embree's QuadLight has corners p, p+vy, p+vx+vy, p+vx; its emitting side was checked
        # against ours by rendering (see docs/ACCURACY.md): vx = edge2, vy = edge1.
        L = [v * light_scale for v in q["radiance"]]
        parts.append("<QuadLight><AffineSpace>%s</AffineSpace><L>%s</L></QuadLight>"
                     % (_space(q["corner"], q["edge2"], q["edge1"]), _floats(L)))
    for mesh in scene["meshes"]:
        mat = scene["materials"][mesh["material"]]
        emission = mat.get("emission", [0, 0, 0])
        if max(emission) > 0:
            P = mesh["positions"]
            L = [v * light_scale for v in emission]
            for a, b, c in mesh["triangles"]:
                # TriangleLight corners: v0 = p + vx, v1 = p + vy, v2 = p (orientation as above).
                v0, v1, v2 = P[a], P[b], P[c]
                vx = [x - y for x, y in zip(v1, v2)]
                vy = [x - y for x, y in zip(v0, v2)]
                parts.append("<TriangleLight><AffineSpace>%s</AffineSpace><L>%s</L></TriangleLight>"
                             % (_space(v2, vx, vy), _floats(L)))
            continue
        parts.append("<TriangleMesh><material>%s</material>" % _material_xml(mat))
        parts.append("<positions>%s</positions>" % " ".join(_floats(p) for p in mesh["positions"]))
        if mesh["normals"]:
            parts.append("<normals>%s</normals>" % " ".join(_floats(n) for n in mesh["normals"]))
        parts.append("<triangles>%s</triangles>" % " ".join("%d %d %d" % tuple(t) for t in mesh["triangles"]))
        parts.append("</TriangleMesh>")
    parts.append("</scene>")
    with open(out_path, "w", encoding="utf-8") as f:
        f.write("\n".join(parts) + "\n")


def camera_args(scene):
    cam = scene["camera"]
    return ["--vp", *map(str, cam["position"]), "--vi", *map(str, cam["look_at"]),
            "--vu", *map(str, cam["up"]), "--fov", str(cam["fov_y"])]


if __name__ == "__main__":
    if len(sys.argv) not in (3, 4):
        raise SystemExit("usage: embree_scene.py scene.json|model.obj out.xml [light_scale]")
    scene = igi_scene.flatten(sys.argv[1])
    write(scene, sys.argv[2], float(sys.argv[3]) if len(sys.argv) == 4 else 1.0)
    print(" ".join(camera_args(scene)))
