"""Flattens an igi scene (scene.json or bare .obj) into world-space triangles for peer renderers.

The peers (Embree's pathtracer, Blender Cycles) cannot read our scene.json, and each reads MTL
files its own way (Embree ignores `illum` and `Ke`; Blender maps MTL to a Principled BSDF). To
compare like with like, this module applies *our* rules (docs/SCENE_FORMAT.md: transforms
T*Rz*Ry*Rx*S, the MTL -> material table, energy clamping, one-sided quad lights) once, and the
peer scripts only translate the result into their own vocabulary.

Standard library only: it runs under /usr/bin/python3 and under Blender's Python.

Output of `flatten(path)` (also written as JSON by `python3 igi_scene.py scene out.json`):
  camera:    {position, look_at, up, fov_y}     (fov_y: vertical, degrees)
  materials: {name: {type: diffuse|glossy|mirror|glass, diffuse, specular, ior, emission,
               texture (absolute path of map_Kd, or absent),
               bump (absolute path of bump / map_bump: a height map, or absent), bump_scale (its -bm, 1)}}
  meshes:    [{name, material, positions: [[x,y,z]], normals: [[x,y,z]] or None,
               uvs: [[u,v]] or None, triangles: [[i,j,k]]}]   (one entry per material and source mesh)
  gltf:      [{file (absolute path), name, matrix (4x4 row-major: our T*Rz*Ry*Rx*S)}]: glTF meshes,
             which the peer imports itself (only Cycles does: Blender's glTF importer)
  quad_lights: [{corner, edge1, edge2, radiance}]   (emit towards cross(edge1, edge2))
  punctual_lights (only with punctual_lights=True): [{type: point|spot|directional, name,
               position, intensity (W/sr), direction (normalized, the way light travels),
               outer_deg, inner_deg (spot), irradiance (W/m^2), angle_deg (directional)}]
  environment: None, {radiance} or {file (absolute path), scale, rotate_deg}
  bounds:    [[minx,miny,minz],[maxx,maxy,maxz]]
"""

import json
import math
import os
import sys


def _vec(value, n=3):
    """A colour or vector given as one number (grey) or a list."""
    if isinstance(value, (int, float)):
        return [float(value)] * n
    return [float(v) for v in value]


def _matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def _rotation(axis, degrees):
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    if axis == 0:
        return [[1, 0, 0], [0, c, -s], [0, s, c]]
    if axis == 1:
        return [[c, 0, s], [0, 1, 0], [-s, 0, c]]
    return [[c, -s, 0], [s, c, 0], [0, 0, 1]]


class Transform:
    """T * Rz * Ry * Rx * S, as docs/SCENE_FORMAT.md defines a mesh entry's transform."""

    def __init__(self, spec=None):
        spec = spec or {}
        scale = _vec(spec.get("scale", 1))
        rot = spec.get("rotate_deg", [0, 0, 0])
        self.translate = _vec(spec.get("translate", [0, 0, 0]))
        r = _matmul(_rotation(2, rot[2]), _matmul(_rotation(1, rot[1]), _rotation(0, rot[0])))
        self.linear = [[r[i][j] * scale[j] for j in range(3)] for i in range(3)]
        # Normals transform with the inverse transpose: R * S^-1 (then renormalised).
        self.normal = [[r[i][j] / scale[j] for j in range(3)] for i in range(3)]

    def point(self, p):
        return [sum(self.linear[i][j] * p[j] for j in range(3)) + self.translate[i] for i in range(3)]

    def direction(self, n):
        d = [sum(self.normal[i][j] * n[j] for j in range(3)) for i in range(3)]
        length = math.sqrt(sum(x * x for x in d)) or 1.0
        return [x / length for x in d]


def _statements(path):
    """(keyword, arguments) of each non-empty line of an OBJ or MTL file, comments dropped."""
    with open(path, encoding="utf-8", errors="replace") as f:
        for line in f:
            words = line.split("#", 1)[0].split()
            if words:
                yield words[0], words[1:]


def _find_file(folder, name):
    """`name` in `folder`, or the file there whose name matches it when case is ignored (our
    loader's rule: Sponza's MTL says 00_SKAP.JPG, the file is 00_skap.JPG)."""
    path = os.path.join(folder, name)
    if os.path.exists(path):
        return path
    head, base = os.path.split(path)
    if os.path.isdir(head):
        for entry in os.listdir(head):
            if entry.lower() == base.lower():
                return os.path.join(head, entry)
    raise SystemExit(f"texture '{name}' not found in {folder}")


def read_mtl(path):
    """MTL statements -> igi materials, following the table in docs/SCENE_FORMAT.md."""
    raw, current = {}, None
    for key, args in _statements(path):
        if key == "newmtl":
            current = raw.setdefault(" ".join(args), {})
        elif current is not None and key == "map_Kd" and args:
            # The last word is the file (options such as -s come before it).
            current["map_Kd"] = _find_file(os.path.dirname(path), args[-1])
        elif current is not None and key in ("bump", "map_bump") and args:
            # A height map (client/materials/BumpMap.h); the last word is the file, -bm its scale.
            current["bump"] = _find_file(os.path.dirname(path), args[-1])
            if "-bm" in args[:-1]:
                current["bump_scale"] = float(args[args.index("-bm") + 1])
        elif current is not None and key in ("Kd", "Ks", "Ke"):
            current[key] = _vec([float(a) for a in args[:3]] if len(args) >= 3 else float(args[0]))
        elif current is not None and key in ("Ns", "Ni"):
            current[key] = float(args[0])
        elif current is not None and key == "illum":
            current[key] = int(args[0])
    return {name: _material_from_mtl(m) for name, m in raw.items()}


def _material_from_mtl(m):
    kd, ks = m.get("Kd", [0.0] * 3), m.get("Ks", [0.0] * 3)
    illum, ni = m.get("illum", 2), m.get("Ni", 0.0)
    mat = {"type": "diffuse", "diffuse": kd, "specular": [0.0] * 3, "ior": 1.5,
           "emission": m.get("Ke", [0.0] * 3), "phong_exponent": m.get("Ns", 1.0)}
    if illum in (3, 5):
        mat.update(type="mirror", specular=ks)
    elif illum in (4, 6, 7):
        mat.update(type="glass", ior=ni if ni > 1.0 else 1.5)
    elif illum == 2 and max(ks) > 0:
        mat.update(type="mirror" if m.get("Ns", 0.0) >= 1000 else "glossy", specular=ks)
    if "map_Kd" in m:
        mat["texture"] = m["map_Kd"]
    if "bump" in m:
        mat["bump"], mat["bump_scale"] = m["bump"], m.get("bump_scale", 1.0)
    total = max(a + b for a, b in zip(mat["diffuse"], mat["specular"]))
    if total > 1.0:
        mat["diffuse"] = [a / total for a in mat["diffuse"]]
        mat["specular"] = [a / total for a in mat["specular"]]
    return mat


def _default_material():
    """Our loader's material for a name it cannot find: grey, Kd 0.8 (docs/SCENE_FORMAT.md)."""
    return {"type": "diffuse", "diffuse": [0.8] * 3, "specular": [0.0] * 3, "ior": 1.5,
            "emission": [0.0] * 3}


def _face_key(points):
    """The set of a face's corner positions (rounded): equal for a face and its twin."""
    return frozenset(tuple(round(c, 6) for c in p) for p in points)


def read_obj(path, transform, mesh_name, drop_duplicate_faces=False, seen_faces=None):
    """Triangulated, world-space groups of one OBJ file, one per material; its materials; and
    the number of faces dropped as duplicates.

    With `drop_duplicate_faces`, a face whose set of corner positions repeats an earlier face's
    (of this file, or of `seen_faces`, a set shared across files) is left out. McGuire's Cornell
    boxes have such twins: CornellBox-Original.obj's tall box lists its front face a second time
    by relative indices (its "bottom face", `f -8 -7 -6 -5`, reuses the front face's vertices),
    and the short box's right face likewise. Our renderer draws a twin on top of its face
    harmlessly; Blender Cycles shadows a face by its twin and renders it nearly black."""
    folder = os.path.dirname(path)
    positions, normals, uvs, materials = [], [], [], {}
    groups, current = {}, "default"
    seen = seen_faces if seen_faces is not None else set()
    dropped = 0
    for key, args in _statements(path):
        if key == "v":
            positions.append(transform.point([float(a) for a in args[:3]]))
        elif key == "vn":
            normals.append(transform.direction([float(a) for a in args[:3]]))
        elif key == "vt":
            uvs.append([float(a) for a in args[:2]] + [0.0] * (2 - len(args[:2])))
        elif key == "mtllib":
            materials.update(read_mtl(os.path.join(folder, " ".join(args))))
        elif key == "usemtl":
            current = " ".join(args)
        elif key == "f":
            corners = []
            for a in args:
                parts = a.split("/")
                vi = int(parts[0])
                vi = vi - 1 if vi > 0 else len(positions) + vi
                ni = ti = None
                if len(parts) >= 3 and parts[2]:
                    ni = int(parts[2])
                    ni = ni - 1 if ni > 0 else len(normals) + ni
                if len(parts) >= 2 and parts[1]:
                    ti = int(parts[1])
                    ti = ti - 1 if ti > 0 else len(uvs) + ti
                corners.append((vi, ni, ti))
            if drop_duplicate_faces:
                key = _face_key([positions[vi] for vi, _, _ in corners])
                if key in seen:
                    dropped += 1
                    continue
                seen.add(key)
            group = groups.setdefault(current, [])
            for k in range(1, len(corners) - 1):
                group.append((corners[0], corners[k], corners[k + 1]))
    # A material the MTL lacks (or no MTL): our loader's default material under that name, which
    # a scene file's "materials" section can then set (CornellBox-Glossy.obj's `light`).
    for name in list(groups) + ["default"]:
        materials.setdefault(name, _default_material())
    meshes = []
    for material, triangles in groups.items():
        index, mesh_pos, mesh_nrm, mesh_uv, tris = {}, [], [], [], []
        has_normals = all(c[1] is not None for t in triangles for c in t)
        # Missing uvs in a mesh that has some are (0, 0), as our loader reads them.
        has_uvs = any(c[2] is not None for t in triangles for c in t)
        for t in triangles:
            ids = []
            for vi, ni, ti in t:
                key = (vi, ni if has_normals else None, ti if has_uvs else None)
                if key not in index:
                    index[key] = len(mesh_pos)
                    mesh_pos.append(positions[vi])
                    if has_normals:
                        mesh_nrm.append(normals[ni])
                    if has_uvs:
                        mesh_uv.append(uvs[ti] if ti is not None else [0.0, 0.0])
                ids.append(index[key])
            tris.append(ids)
        meshes.append({"name": f"{mesh_name}/{material}", "material": material,
                       "positions": mesh_pos, "normals": mesh_nrm if has_normals else None,
                       "uvs": mesh_uv if has_uvs else None, "triangles": tris})
    return meshes, materials, dropped


def _frame_camera(bounds, width, height):
    """The camera our loader gives a scene without one: looks at the bounds' centre from +Z."""
    lo, hi = bounds
    centre = [(a + b) / 2 for a, b in zip(lo, hi)]
    radius = math.sqrt(sum(((b - a) / 2) ** 2 for a, b in zip(lo, hi)))
    half = math.radians(45.0) / 2
    if height > width:  # portrait: the horizontal field of view is the narrow one
        half = math.atan(math.tan(half) * width / height)
    distance = radius / math.sin(half)
    return {"position": [centre[0], centre[1], centre[2] + distance], "look_at": centre,
            "up": [0.0, 1.0, 0.0], "fov_y": 45.0}


def flatten(scene_path, width=None, height=None, drop_duplicate_faces=False, punctual_lights=False):
    """The scene as world-space triangles (see the module's docstring). With
    `drop_duplicate_faces`, faces that repeat another face's corners are left out (read_obj);
    their number is returned as "dropped_duplicate_faces". With `punctual_lights` (a peer that
    can render them: Cycles), point, spot and directional lights and the environment are
    returned too; without it they are an error, as before."""
    if scene_path.lower().endswith(".obj"):
        spec = {"meshes": [{"file": os.path.basename(scene_path)}]}
    else:
        with open(scene_path, encoding="utf-8") as f:
            spec = json.load(f)
    folder = os.path.dirname(os.path.abspath(scene_path))
    image = spec.get("image", {})
    width = width or image.get("width", 640)
    height = height or image.get("height", 480)

    meshes, materials, dropped, seen_faces, gltf = [], {}, 0, set(), []
    for entry in spec.get("meshes", []):
        path = os.path.join(folder, entry["file"])
        name = entry.get("name", os.path.splitext(os.path.basename(path))[0])
        if path.lower().endswith((".gltf", ".glb")):
            t = Transform(entry.get("transform"))
            matrix = [t.linear[i] + [t.translate[i]] for i in range(3)] + [[0.0, 0.0, 0.0, 1.0]]
            gltf.append({"file": os.path.abspath(path), "name": name, "matrix": matrix})
            continue
        m, mats, d = read_obj(path, Transform(entry.get("transform")), name, drop_duplicate_faces, seen_faces)
        dropped += d
        # Materials are per file in igi; names are unique across these scenes' files, so one
        # dictionary is enough here (a clash would be reported rather than silently merged).
        for key, value in mats.items():
            if key in materials and materials[key] != value:
                raise SystemExit(f"{path}: material '{key}' differs from one of the same name")
            materials[key] = value
        meshes += m
    for name, override in spec.get("materials", {}).items():
        materials.setdefault(name, _default_material())
        for key, value in override.items():
            materials[name][key] = value if key in ("type", "ior", "phong_exponent") else _vec(value)

    quads, punctual = [], []
    for light in spec.get("lights", []):
        kind = light["type"]
        if kind == "quad":
            quads.append({"corner": _vec(light["corner"]), "edge1": _vec(light["edge1"]),
                          "edge2": _vec(light["edge2"]), "radiance": _vec(light["radiance"])})
        elif punctual_lights and kind in ("point", "spot", "directional"):
            out = {"type": kind, "name": light.get("name", f"light{len(quads) + len(punctual)}")}
            if kind in ("point", "spot"):
                out.update(position=_vec(light["position"]), intensity=_vec(light["intensity"]))
            if kind in ("spot", "directional"):
                d = _vec(light["direction"])
                n = math.sqrt(sum(x * x for x in d))
                out["direction"] = [x / n for x in d]
            if kind == "spot":
                out.update(outer_deg=float(light.get("outer_deg", 45.0)), inner_deg=float(light.get("inner_deg", 0.0)))
            if kind == "directional":
                out.update(irradiance=_vec(light["irradiance"]), angle_deg=float(light.get("angle_deg", 0.0)))
            punctual.append(out)
        else:
            raise SystemExit(f"{scene_path}: light type '{kind}' is not exported to this peer")
    environment = None
    if "environment" in spec:
        if not punctual_lights:
            raise SystemExit(f"{scene_path}: the environment is not exported to this peer")
        env = spec["environment"]
        if "file" in env:
            environment = {"file": os.path.join(folder, env["file"]), "scale": _vec(env.get("scale", 1)),
                           "rotate_deg": float(env.get("rotate_deg", 0.0))}
        else:
            environment = {"radiance": _vec(env["radiance"])}
    if spec.get("headlight"):
        raise SystemExit(f"{scene_path}: headlights are not exported to peers")

    points = [p for m in meshes for p in m["positions"]]
    for q in quads:
        c, e1, e2 = q["corner"], q["edge1"], q["edge2"]
        points += [c, [a + b for a, b in zip(c, e1)], [a + b for a, b in zip(c, e2)],
                   [a + b + d for a, b, d in zip(c, e1, e2)]]
    bounds = None
    if points:
        bounds = [[min(p[i] for p in points) for i in range(3)], [max(p[i] for p in points) for i in range(3)]]
    camera = spec.get("camera")
    if camera is None:
        if gltf or not points:
            raise SystemExit(f"{scene_path}: a scene with glTF meshes needs a camera for this peer")
        camera = _frame_camera(bounds, width, height)
    camera = {"position": _vec(camera["position"]), "look_at": _vec(camera["look_at"]),
              "up": _vec(camera.get("up", [0, 1, 0])), "fov_y": float(camera.get("fov_y", 45.0))}
    return {"camera": camera, "width": width, "height": height, "materials": materials,
            "meshes": meshes, "gltf": gltf, "quad_lights": quads, "punctual_lights": punctual, "environment": environment,
            "bounds": bounds, "dropped_duplicate_faces": dropped}


if __name__ == "__main__":
    if len(sys.argv) != 3:
        raise SystemExit("usage: igi_scene.py scene.json|model.obj out.json")
    with open(sys.argv[2], "w", encoding="utf-8") as out:
        json.dump(flatten(sys.argv[1]), out)
