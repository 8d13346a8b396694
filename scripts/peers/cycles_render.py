"""Renders an igi scene with Blender Cycles (CPU), headless, to linear OpenEXR.

Usage:
  blender -b --factory-startup -P scripts/peers/cycles_render.py -- \
      SCENE OUT_PREFIX WIDTH HEIGHT THREADS SPP [SPP ...] [--until[-cpu] SECONDS [--max-spp N]] [--seed N]

Writes OUT_PREFIX-<spp>spp.exr for every sample count, and OUT_PREFIX.json with the render time
of each (seconds spent in bpy.ops.render.render, i.e. scene sync, BVH build and path tracing,
and the CPU seconds of all of Blender's threads over the same span;
Blender's own start-up is measured separately as "startup_seconds", and a first, unrecorded
1-spp render as "warmup_seconds"). With --until, after the
listed counts the count doubles, render after render, until one render has taken SECONDS or
more (or the count would pass --max-spp, 65536 by default): the curve then spans that time.
--until-cpu SECONDS is --until counted in CPU seconds per thread (the render's CPU time over
THREADS): on a machine shared with others, the time the render would take on THREADS cores of
its own. --seed sets Cycles' seed (1 by default): a reference rendered with another seed is independent
of the images it judges.

Faces whose corners repeat another face's are dropped first (igi_scene.read_obj: Cycles shadows
a face by its twin, and McGuire's CornellBox-Original.obj has two); the JSON says how many.

The scene is flattened by igi_scene.py (our transforms and MTL interpretation), then rebuilt
with explicit Cycles shaders so that materials mean the same thing in both renderers:
  diffuse -> Diffuse BSDF (roughness 0 = Lambert); mirror -> Glossy BSDF "Sharp" (+ diffuse);
  glass -> Glass BSDF "Sharp" with our IOR and white tint; glossy -> Diffuse + Glossy (GGX with
  roughness from the Phong exponent: an approximation); emission -> Emission on the front face
  only (Cycles emits from both sides; we do not), plus the diffuse part.
Lights (igi_scene.flatten(..., punctual_lights=True)):
  quad -> a one-sided emissive mesh (above).
  point (intensity I, W/sr) -> POINT of power 4 pi I W, radius 0 (Cycles' point light of power
    P gives P / (4 pi) W/sr: checked on a diffuse floor against I cos^3 / h^2 albedo / pi, 0.1 %).
  spot -> SPOT of the same power on its axis, radius 0, spot_size = 2 outer, spot_blend =
    (cos inner - cos outer) / (1 - cos outer), so Cycles' ramp spans the same cosines. The ramp
    is not ours: Cycles (3.4) multiplies by smoothstep over that span, ours (glTF's) by t^2 with t
    linear in the cosine, and Cycles 3.4 also multiplies a spot by cos a (a from the axis: 2 %
    less at 11 degrees, 13 % at 30). A spot-lit Cycles image is a reference only up to that.
  directional (irradiance E, W/m^2, travelling along `direction`) -> SUN of strength E aimed
    along `direction`, angle = angle_deg. Unlike ours, Cycles' sun disk is visible to rays that
    leave the scene through mirrors and glass.
  environment -> world Background of strength 1: a constant colour, or an Environment Texture
    (equirectangular, Closest, linear colour space) times `scale`, looked up through a Mapping
    node that turns our Y-up directions into Blender's (x, -z, y) and then by -rotate_deg
    about Blender's Z (our +Y).
Film: box pixel filter of 1 pixel (each sample uniform in its pixel, as ours), no denoising, no
adaptive sampling, no clamping, no filter-glossy, caustics on, 16 bounces like our reference.
Colour: EXR is written scene-linear (no view transform); Blender's working space is linear
Rec.709, as ours.
"""

import json
import os
import sys
import time

START = time.time()
import bpy  # noqa: E402

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import igi_scene  # noqa: E402


def _rgba(c):
    return (c[0], c[1], c[2], 1.0)


_IMAGES = {}


def _image(path):
    """A texture, loaded once (8-bit images as sRGB, Blender's default for them)."""
    if path not in _IMAGES:
        _IMAGES[path] = bpy.data.images.load(path)
    return _IMAGES[path]


def _bump_normal(nodes, links, path, scale):
    """Our height map (client/materials/BumpMap.h) as a shading normal: the tangent-space normal
    (-scale dh/du, -scale dh/dv, 1), slopes by central differences one texel apart in height per
    texel (h: the mean of the linear channels, bilinear, wrapping), into a tangent-space Normal
    Map node on the UV map (Blender's MikkTSpace tangents; ours come from each triangle's uv
    derivatives). Cycles' own Bump node differentiates in screen space per unit of length,
    which would tie the tilt to the scene's scale; this does not."""
    image = bpy.data.images.load(path, check_existing=False)
    image.colorspace_settings.name = "Non-Color"
    w, h = max(image.size[0], 1), max(image.size[1], 1)
    uv = nodes.new("ShaderNodeUVMap")
    uv.uv_map = "UVMap"

    def height_at(du, dv):
        shift = nodes.new("ShaderNodeVectorMath")
        shift.operation = "ADD"
        shift.inputs[1].default_value = (du, dv, 0.0)
        links.new(uv.outputs["UV"], shift.inputs[0])
        tex = nodes.new("ShaderNodeTexImage")
        tex.image = image
        tex.interpolation = "Linear"
        tex.extension = "REPEAT"
        links.new(shift.outputs["Vector"], tex.inputs["Vector"])
        mean = nodes.new("ShaderNodeVectorMath")
        mean.operation = "DOT_PRODUCT"
        mean.inputs[1].default_value = (1 / 3, 1 / 3, 1 / 3)
        links.new(tex.outputs["Color"], mean.inputs[0])
        return mean.outputs["Value"]

    def slope(plus, minus):
        d = nodes.new("ShaderNodeMath")
        d.operation = "SUBTRACT"
        links.new(plus, d.inputs[0])
        links.new(minus, d.inputs[1])
        m = nodes.new("ShaderNodeMath")
        m.operation = "MULTIPLY"
        m.inputs[1].default_value = -0.5 * scale
        links.new(d.outputs[0], m.inputs[0])
        return m.outputs[0]

    n = nodes.new("ShaderNodeCombineXYZ")
    links.new(slope(height_at(1 / w, 0), height_at(-1 / w, 0)), n.inputs["X"])
    links.new(slope(height_at(0, 1 / h), height_at(0, -1 / h)), n.inputs["Y"])
    n.inputs["Z"].default_value = 1.0
    unit = nodes.new("ShaderNodeVectorMath")
    unit.operation = "NORMALIZE"
    links.new(n.outputs["Vector"], unit.inputs[0])
    colour = nodes.new("ShaderNodeVectorMath")  # n / 2 + 1 / 2, as a normal map stores it
    colour.operation = "MULTIPLY_ADD"
    colour.inputs[1].default_value = (0.5, 0.5, 0.5)
    colour.inputs[2].default_value = (0.5, 0.5, 0.5)
    links.new(unit.outputs["Vector"], colour.inputs[0])
    nm = nodes.new("ShaderNodeNormalMap")
    nm.space = "TANGENT"
    nm.uv_map = "UVMap"
    nm.inputs["Strength"].default_value = 1.0
    links.new(colour.outputs["Vector"], nm.inputs["Color"])
    return nm.outputs["Normal"]


def _material(name, mat):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nodes, links = m.node_tree.nodes, m.node_tree.links
    nodes.clear()
    out = nodes.new("ShaderNodeOutputMaterial")

    normal = _bump_normal(nodes, links, mat["bump"], mat.get("bump_scale", 1.0)) if mat.get("bump") else None

    def diffuse():
        d = nodes.new("ShaderNodeBsdfDiffuse")
        d.inputs["Color"].default_value = _rgba(mat["diffuse"])
        d.inputs["Roughness"].default_value = 0.0
        if normal is not None:
            links.new(normal, d.inputs["Normal"])
        if mat.get("texture"):
            # Kd x map_Kd, bilinear, wrapping, sRGB-decoded: as our TextureLoader.
            tex = nodes.new("ShaderNodeTexImage")
            tex.image = _image(mat["texture"])
            tex.interpolation = "Linear"
            tex.extension = "REPEAT"
            uv = nodes.new("ShaderNodeUVMap")
            uv.uv_map = "UVMap"
            links.new(uv.outputs["UV"], tex.inputs["Vector"])
            mul = nodes.new("ShaderNodeMixRGB")
            mul.blend_type = "MULTIPLY"
            mul.inputs["Fac"].default_value = 1.0
            mul.inputs["Color1"].default_value = _rgba(mat["diffuse"])
            links.new(tex.outputs["Color"], mul.inputs["Color2"])
            links.new(mul.outputs["Color"], d.inputs["Color"])
        return d.outputs[0]

    def add(a, b):
        n = nodes.new("ShaderNodeAddShader")
        links.new(a, n.inputs[0])
        links.new(b, n.inputs[1])
        return n.outputs[0]

    kind = mat["type"]
    if kind == "glass":
        g = nodes.new("ShaderNodeBsdfGlass")
        g.distribution = "SHARP"
        g.inputs["Color"].default_value = (1, 1, 1, 1)
        g.inputs["IOR"].default_value = mat["ior"]
        surface = g.outputs[0]
    elif kind in ("mirror", "glossy"):
        g = nodes.new("ShaderNodeBsdfGlossy")
        if kind == "mirror":
            g.distribution = "SHARP"
        else:
            g.distribution = "GGX"
            # Phong exponent n ~ 2 / alpha^2 - 2 (Walter et al. 2007), alpha = roughness^2.
            alpha = (2.0 / (mat.get("phong_exponent", 10.0) + 2.0)) ** 0.5
            g.inputs["Roughness"].default_value = alpha ** 0.5
        g.inputs["Color"].default_value = _rgba(mat["specular"])
        if normal is not None:
            links.new(normal, g.inputs["Normal"])
        surface = add(diffuse(), g.outputs[0]) if max(mat["diffuse"]) > 0 else g.outputs[0]
    else:
        surface = diffuse()

    emission = mat.get("emission", [0, 0, 0])
    if max(emission) > 0:
        e = nodes.new("ShaderNodeEmission")
        e.inputs["Color"].default_value = _rgba(emission)
        e.inputs["Strength"].default_value = 1.0
        front = add(surface, e.outputs[0])
        mix = nodes.new("ShaderNodeMixShader")
        geo = nodes.new("ShaderNodeNewGeometry")
        links.new(geo.outputs["Backfacing"], mix.inputs[0])
        links.new(front, mix.inputs[1])
        links.new(surface, mix.inputs[2])
        surface = mix.outputs[0]
    links.new(surface, out.inputs["Surface"])
    return m


def _quad_material(radiance):
    """Our quad lights: emit from the front, black (no reflection) otherwise."""
    return _material("quad_light", {"type": "diffuse", "diffuse": [0, 0, 0], "emission": radiance})


def _add_mesh(name, positions, triangles, normals, material, uvs=None):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([tuple(p) for p in positions], [], [tuple(t) for t in triangles])
    mesh.update()
    if uvs:
        layer = mesh.uv_layers.new(name="UVMap")
        flat = [c for loop in mesh.loops for c in uvs[loop.vertex_index]]
        layer.data.foreach_set("uv", flat)
    if normals:
        mesh.use_auto_smooth = True
        for poly in mesh.polygons:
            poly.use_smooth = True
        mesh.normals_split_custom_set_from_vertices([tuple(n) for n in normals])
    mesh.materials.append(material)
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)


# "principled" (default): the Principled BSDFs as imported (Burley diffuse); "lambert"
# (IGI_CYCLES_DIFFUSE=lambert): each one's diffuse lobe swapped for a Lambertian Diffuse BSDF
# (_lambert_diffuse), to measure Burley against Lambert alone; "spec" (IGI_CYCLES_DIFFUSE=spec):
# that Lambertian lobe also weighted by 1 - f0, the glTF specification's diffuse weight 1 - F(v.h)
# at its largest (F >= f0), to measure all that Principled's diffuse departs from the
# specification by (Burley, and no Fresnel weight), taken at its smallest.
DIFFUSE = os.environ.get("IGI_CYCLES_DIFFUSE", "principled")
if DIFFUSE not in ("principled", "lambert", "spec"):
    sys.exit(f"cycles_render: IGI_CYCLES_DIFFUSE={DIFFUSE!r}: expected principled, lambert or spec")


# "bytes" (default): 8-bit sRGB textures as Blender loads them, which Cycles interpolates in
# sRGB and only then decodes (svm_image: color_srgb_to_linear after the lookup); "linear"
# (IGI_CYCLES_TEXTURES=linear): each such image decoded to linear floats first
# (_linear_texture), so that Cycles filters linear values as the glTF specification asks and as
# we do. Across a sharp edge of texels the two differ: sRGB interpolation darkens the blend.
TEXTURES = os.environ.get("IGI_CYCLES_TEXTURES", "bytes")
if TEXTURES not in ("bytes", "linear"):
    sys.exit(f"cycles_render: IGI_CYCLES_TEXTURES={TEXTURES!r}: expected bytes or linear")


def _linear_texture(image):
    """A float copy of the 8-bit sRGB `image` with its colour decoded to linear (alpha kept), in
    the "Linear" colour space, or None when `image` is not 8-bit sRGB."""
    import numpy

    if image.is_float or image.colorspace_settings.name != "sRGB" or image.size[0] == 0:
        return None
    w, h = image.size
    px = numpy.empty(w * h * 4, dtype=numpy.float32)
    image.pixels.foreach_get(px)  # the bytes / 255, not colour managed
    px = px.reshape(-1, 4)
    c = px[:, :3]
    px[:, :3] = numpy.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    out = bpy.data.images.new(image.name + " (linear)", w, h, alpha=True, float_buffer=True)
    out.colorspace_settings.name = "Linear"
    out.alpha_mode = "CHANNEL_PACKED"
    out.pixels.foreach_set(px.ravel())
    return out


def _source(socket):
    """The socket linked into `socket`, or None."""
    return socket.links[0].from_socket if socket.is_linked else None


def _alpha_cut_off(material, principled):
    """glTF alphaMode MASK: Blender 3.4's importer makes it blend_method CLIP with
    alpha_threshold = alphaCutoff, which only EEVEE reads (Cycles blends by the alpha). So the
    alpha going into the Principled BSDF becomes 1 where alpha >= cutoff and 0 elsewhere (ours:
    docs/MATERIALS.md, "Alpha"): 1 - (alpha < cutoff)."""
    nodes, links = material.node_tree.nodes, material.node_tree.links
    cutoff = material.alpha_threshold
    socket = principled.inputs["Alpha"]
    src = _source(socket)
    if src is None:
        socket.default_value = 1.0 if socket.default_value >= cutoff else 0.0
    else:
        below = nodes.new("ShaderNodeMath")
        below.operation = "LESS_THAN"
        below.inputs[1].default_value = cutoff
        links.new(src, below.inputs[0])
        keep = nodes.new("ShaderNodeMath")
        keep.operation = "SUBTRACT"
        keep.inputs[0].default_value = 1.0
        links.new(below.outputs[0], keep.inputs[1])
        links.new(keep.outputs[0], socket)
    material.blend_method = "BLEND"  # what Cycles does anyway; the cut is in the nodes now
    print(f"cycles: {material.name}: alpha MASK at {cutoff:g} applied in the shader", flush=True)


def _lambert_diffuse(material, principled, fresnel_weight):
    """Principled (v1, Blender 3.x) = Burley diffuse x base colour x (1 - metallic)(1 -
    transmission) + the specular lobes, the diffuse not weighted by the specular's Fresnel.
    Swapped: the Principled with a black base colour (its specular lobes only: specular tint 0,
    as the importer leaves it) plus a Diffuse BSDF of roughness 0 (Lambert) with that base colour
    times the same weight and the same normal; with `fresnel_weight` also times 1 - f0, f0 =
    0.08 x Specular (Principled's own mapping: 0.5 is f0 0.04, the specification's ior 1.5). Only
    for opaque dielectrics (metallic 0) with constant transmission and specular (the Burley
    scene's); others are left as they are, with a message."""
    nodes, links = material.node_tree.nodes, material.node_tree.links
    ins = principled.inputs
    if ins["Metallic"].is_linked or ins["Transmission"].is_linked or ins["Alpha"].is_linked \
            or ins["Alpha"].default_value < 1 or ins["Subsurface"].default_value > 0 \
            or ins["Metallic"].default_value > 0 or (fresnel_weight and ins["Specular"].is_linked):
        # A metallic > 0 takes its specular colour from the base colour, which the swap blackens;
        # metallic 1 has no diffuse lobe to swap.
        print(f"cycles: {material.name}: diffuse left as Burley (not a constant opaque dielectric)", flush=True)
        return
    weight = (1 - ins["Metallic"].default_value) * (1 - ins["Transmission"].default_value)
    if fresnel_weight:
        weight *= 1 - 0.08 * ins["Specular"].default_value
    d = nodes.new("ShaderNodeBsdfDiffuse")
    d.inputs["Roughness"].default_value = 0.0
    colour = nodes.new("ShaderNodeMixRGB")
    colour.blend_type = "MULTIPLY"
    colour.inputs["Fac"].default_value = 1.0
    colour.inputs["Color2"].default_value = (weight, weight, weight, 1.0)
    base = _source(ins["Base Color"])
    if base is None:
        colour.inputs["Color1"].default_value = ins["Base Color"].default_value
    else:
        links.new(base, colour.inputs["Color1"])
        links.remove(ins["Base Color"].links[0])
    links.new(colour.outputs["Color"], d.inputs["Color"])
    ins["Base Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    if ins["Normal"].is_linked:
        links.new(_source(ins["Normal"]), d.inputs["Normal"])
    add = nodes.new("ShaderNodeAddShader")
    targets = [l.to_socket for l in principled.outputs["BSDF"].links]
    links.new(principled.outputs["BSDF"], add.inputs[0])
    links.new(d.outputs["BSDF"], add.inputs[1])
    for t in targets:
        links.new(add.outputs["Shader"], t)
    print(f"cycles: {material.name}: diffuse swapped for Lambert (weight {weight:g})", flush=True)


def _import_gltf(model):
    """A glTF mesh of the scene file through Blender's own importer (its lights in the
    importer's "Standard" lighting mode, its default, asked for by name: `convert_lighting_mode`
    in Debian's 3.4, `export_import_convert_lighting_mode` in later versions; it converts lux
    and candela as we do: docs/SCENE_FORMAT.md, checked by scripts/gltf_light_units.sh),
    then put where our scene puts it: the importer turns glTF's Y-up into Blender's Z-up,
    (x, y, z) -> (x, -z, y), which this script's scene (ours, unchanged) does not; so the
    imported roots hang under an empty of matrix (our transform) x (that turn undone).
    Principled BSDFs get "GGX" (single scattering, as ours), not "Multiscatter GGX"; their
    diffuse stays Burley (ours is Lambert: docs/MATERIALS.md)."""
    import math

    import mathutils
    import numpy

    if not hasattr(numpy, "bool"):
        numpy.bool = bool  # Blender 3.4's importer uses numpy.bool, gone from numpy >= 1.24
    before = set(bpy.data.objects)
    images_before = set(bpy.data.images)
    options = {}
    props = bpy.ops.import_scene.gltf.get_rna_type().properties
    for name in ("convert_lighting_mode", "export_import_convert_lighting_mode"):
        if name in props.keys():
            options[name] = "SPEC"
    bpy.ops.import_scene.gltf(filepath=model["file"], **options)
    new = [o for o in bpy.data.objects if o not in before]
    for image in bpy.data.images:
        if image not in images_before:
            # glTF colours are not premultiplied by alpha, and OPAQUE ignores alpha altogether;
            # a Cycles image texture whose Alpha output is unused returns its colour premultiplied
            # (black where alpha is 0) unless the image's alpha is "channel packed".
            image.alpha_mode = "CHANNEL_PACKED"
    if TEXTURES == "linear":
        swapped = {}
        for image in [i for i in bpy.data.images if i not in images_before]:
            linear = _linear_texture(image)
            if linear is not None:
                swapped[image] = linear
        for material in bpy.data.materials:
            for node in (material.node_tree.nodes if material.use_nodes else []):
                if node.type == "TEX_IMAGE" and node.image in swapped:
                    node.image = swapped[node.image]
        print(f"cycles: {len(swapped)} sRGB textures decoded to linear floats before filtering", flush=True)
    seen = set()
    root = bpy.data.objects.new(model["name"] + "_root", None)
    bpy.context.scene.collection.objects.link(root)
    root.matrix_world = mathutils.Matrix(model["matrix"]) @ mathutils.Matrix.Rotation(-math.pi / 2, 4, "X")
    for o in new:
        if o.parent is None:
            o.parent = root
    for o in new:
        # glTF's punctual lights are points and a delta sun; Blender's importer leaves new
        # lights' default size (a 0.25 m sphere, which lights a floor 1.4 m below 3 % less).
        if o.type == "LIGHT":
            if o.data.type == "SUN":
                o.data.angle = 0.0
            else:
                o.data.shadow_soft_size = 0.0
        for slot in getattr(o, "material_slots", []):
            if slot.material and slot.material.use_nodes and slot.material not in seen:
                seen.add(slot.material)
                for node in list(slot.material.node_tree.nodes):
                    if node.type == "BSDF_PRINCIPLED":
                        node.distribution = "GGX"
                        if slot.material.blend_method == "CLIP":
                            _alpha_cut_off(slot.material, node)
                        if DIFFUSE != "principled":
                            _lambert_diffuse(slot.material, node, DIFFUSE == "spec")
    print(f"cycles: imported {model['file']}: {len(new)} objects", flush=True)


def _camera(cam, width, height):
    import mathutils

    data = bpy.data.cameras.new("camera")
    data.sensor_fit = "VERTICAL"
    import math

    data.angle_y = math.radians(cam["fov_y"])
    obj = bpy.data.objects.new("camera", data)
    bpy.context.scene.collection.objects.link(obj)
    eye = mathutils.Vector(cam["position"])
    forward = (mathutils.Vector(cam["look_at"]) - eye).normalized()
    up = mathutils.Vector(cam["up"])
    right = forward.cross(up).normalized()
    true_up = right.cross(forward)
    # A Blender camera looks down its local -Z with +Y up.
    rot = mathutils.Matrix((right, true_up, -forward)).transposed()
    obj.matrix_world = mathutils.Matrix.Translation(eye) @ rot.to_4x4()
    bpy.context.scene.camera = obj


def _colour_and_strength(rgb):
    """A Blender light's colour (max channel 1) and strength for per-channel values."""
    m = max(rgb)
    if m <= 0:
        return (0.0, 0.0, 0.0), 0.0
    return tuple(c / m for c in rgb), m


def _aim(obj, direction):
    """Turns a light so that its local -Z (where Blender's sun and spot shine) is `direction`."""
    import mathutils

    d = mathutils.Vector(direction).normalized()
    obj.rotation_euler = (-d).to_track_quat("Z", "Y").to_euler()


# "ours" (default): a Cycles spot given glTF's ramp by a light shader (_spot_ramp_nodes);
# "cycles": Cycles' own smoothstep blend over the same cosines (IGI_CYCLES_SPOT_RAMP=cycles).
SPOT_RAMP = os.environ.get("IGI_CYCLES_SPOT_RAMP", "ours")


def _spot_ramp_nodes(data, cos_inner, cos_outer):
    """A light shader on a Cycles spot (blend 0) that turns Cycles' weight, cos a, into glTF's
    t^2 with t = clamp((cos a - cos outer) / (cos inner - cos outer), 0, 1). The direction
    toward the shaded point in the light's own frame is the Texture Coordinate node's Normal
    (what gobo projections use); the spot shines along local -Z, so cos a = -Normal.z."""
    data.use_nodes = True
    nodes, links = data.node_tree.nodes, data.node_tree.links
    emission = next(n for n in nodes if n.type == "EMISSION")
    coords = nodes.new("ShaderNodeTexCoord")
    split = nodes.new("ShaderNodeSeparateXYZ")
    links.new(coords.outputs["Normal"], split.inputs[0])

    def math_node(op, a, b=None, clamp=False):
        n = nodes.new("ShaderNodeMath")
        n.operation = op
        n.use_clamp = clamp
        for i, v in enumerate((a, b)):
            if v is None:
                continue
            if isinstance(v, (int, float)):
                n.inputs[i].default_value = v
            else:
                links.new(v, n.inputs[i])
        return n.outputs[0]

    cos_a = math_node("MULTIPLY", split.outputs["Z"], -1.0)
    span = max(cos_inner - cos_outer, 1e-6)
    t = math_node("MULTIPLY", math_node("SUBTRACT", cos_a, cos_outer), 1.0 / span, clamp=True)
    weight = math_node("DIVIDE", math_node("MULTIPLY", t, t), math_node("MAXIMUM", cos_a, 1e-6))
    links.new(weight, emission.inputs["Strength"])


def _punctual_light(light):
    """Our point, spot and directional lights as Blender lights (module docstring)."""
    import math

    kind = light["type"]
    if kind == "directional":
        data = bpy.data.lights.new(light["name"], "SUN")
        colour, data.energy = _colour_and_strength(light["irradiance"])  # W/m^2, as ours
        data.angle = math.radians(light["angle_deg"])
    else:
        data = bpy.data.lights.new(light["name"], "POINT" if kind == "point" else "SPOT")
        colour, strength = _colour_and_strength(light["intensity"])
        # Blender's point and spot power P (W) gives intensity P / (4 pi) W/sr (on a spot's axis).
        data.energy = 4.0 * math.pi * strength
        data.shadow_soft_size = 0.0
        if kind == "spot":
            outer, inner = math.radians(light["outer_deg"]), math.radians(light["inner_deg"])
            data.spot_size = 2.0 * outer
            data.show_cone = False
            if SPOT_RAMP == "cycles":
                # Cycles ramps with smoothstep over cos a from cos(outer) to cos(outer) + blend (1 -
                # cos(outer)); glTF's (ours) is t^2 over [cos outer, cos inner]. Same end points:
                data.spot_blend = (math.cos(inner) - math.cos(outer)) / (1.0 - math.cos(outer))
            else:
                # Ours exactly: no blend (Cycles 3.4 then weighs a direction at angle a from the
                # axis by cos a alone) and a light shader that multiplies by t^2 / cos a.
                data.spot_blend = 0.0
                _spot_ramp_nodes(data, math.cos(inner), math.cos(outer))
    data.color = colour
    data.cycles.cast_shadow = True
    data.cycles.max_bounces = 1024
    obj = bpy.data.objects.new(light["name"], data)
    if kind != "directional":
        obj.location = light["position"]
    if kind != "point":
        _aim(obj, light["direction"])
    bpy.context.scene.collection.objects.link(obj)


def _world(environment):
    """Black, a constant sky, or an equirectangular map oriented as ours (module docstring)."""
    import math

    world = bpy.data.worlds.new("environment")
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    background = nodes["Background"]
    if environment is None:
        background.inputs["Strength"].default_value = 0.0
    elif "radiance" in environment:
        background.inputs["Color"].default_value = _rgba(environment["radiance"])
        background.inputs["Strength"].default_value = 1.0
    else:
        coords = nodes.new("ShaderNodeTexCoord")
        mapping = nodes.new("ShaderNodeMapping")
        mapping.vector_type = "POINT"
        # Our scene goes into Blender unchanged (our Y is Blender's Z axis here), but the map's
        # orientation is Blender's once the glTF importer's axes apply: Blender (x, y, z) =
        # ours (x, -z, y), i.e. a +90 degree turn about X. Then the sky turned by rotate_deg
        # about +Y (Blender +Z) is looked up at the direction turned back: Rz(-r) Rx(90).
        # The Mapping node's Euler rotation is XYZ (Rz Ry Rx applied to the vector).
        mapping.inputs["Rotation"].default_value = (math.radians(90.0), 0.0,
                                                    -math.radians(environment["rotate_deg"]))
        tex = nodes.new("ShaderNodeTexEnvironment")
        tex.image = bpy.data.images.load(environment["file"])
        tex.image.colorspace_settings.name = "Linear"
        tex.interpolation = "Closest"
        tex.projection = "EQUIRECTANGULAR"
        scale = nodes.new("ShaderNodeMixRGB")
        scale.blend_type = "MULTIPLY"
        scale.inputs["Fac"].default_value = 1.0
        scale.inputs["Color2"].default_value = _rgba(environment["scale"])
        links.new(coords.outputs["Generated"], mapping.inputs["Vector"])
        links.new(mapping.outputs["Vector"], tex.inputs["Vector"])
        links.new(tex.outputs["Color"], scale.inputs["Color1"])
        links.new(scale.outputs["Color"], background.inputs["Color"])
        background.inputs["Strength"].default_value = 1.0
    return world


def main(argv):
    until, max_spp = None, 65536
    if "--max-spp" in argv:
        i = argv.index("--max-spp")
        max_spp = int(argv[i + 1])
        del argv[i:i + 2]
    until_cpu = False
    if "--until-cpu" in argv:
        i = argv.index("--until-cpu")
        argv[i] = "--until"
        until_cpu = True
    seed = 1
    if "--seed" in argv:
        i = argv.index("--seed")
        seed = int(argv[i + 1])
        del argv[i:i + 2]
    if "--until" in argv:
        i = argv.index("--until")
        until = float(argv[i + 1])
        del argv[i:i + 2]
    scene_path, prefix, width, height, threads = argv[0], argv[1], int(argv[2]), int(argv[3]), int(argv[4])
    spps = [int(a) for a in argv[5:]] or [1]
    flat = igi_scene.flatten(scene_path, width, height, drop_duplicate_faces=True, punctual_lights=True)
    if flat["dropped_duplicate_faces"]:
        print(f"cycles: dropped {flat['dropped_duplicate_faces']} face(s) repeating another face's corners", flush=True)

    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    materials = {name: _material(name, m) for name, m in flat["materials"].items()}
    for mesh in flat["meshes"]:
        _add_mesh(mesh["name"], mesh["positions"], mesh["triangles"], mesh["normals"], materials[mesh["material"]],
                  mesh.get("uvs"))
    for model in flat.get("gltf", []):
        _import_gltf(model)
    for i, q in enumerate(flat["quad_lights"]):
        c, e1, e2 = q["corner"], q["edge1"], q["edge2"]
        p = [c, [a + b for a, b in zip(c, e1)], [a + b + d for a, b, d in zip(c, e1, e2)], [a + b for a, b in zip(c, e2)]]
        # Vertex order c, c+e1, c+e1+e2, c+e2: Blender's face normal is cross(e1, e2), our front.
        _add_mesh(f"quad_light{i}", p, [[0, 1, 2], [0, 2, 3]], None, _quad_material(q["radiance"]))
    for light in flat["punctual_lights"]:
        _punctual_light(light)
    _camera(flat["camera"], width, height)

    scene = bpy.context.scene
    scene.world = _world(flat["environment"])
    scene.render.engine = "CYCLES"
    cycles = scene.cycles
    cycles.device = "CPU"
    cycles.use_adaptive_sampling = False
    cycles.use_denoising = False
    cycles.sample_clamp_direct = 0.0
    cycles.sample_clamp_indirect = 0.0
    cycles.blur_glossy = 0.0
    cycles.caustics_reflective = True
    cycles.caustics_refractive = True
    cycles.max_bounces = 16
    cycles.diffuse_bounces = 16
    cycles.glossy_bounces = 16
    cycles.transmission_bounces = 16
    cycles.transparent_max_bounces = 16
    cycles.pixel_filter_type = "BOX"
    cycles.filter_width = 1.0
    cycles.seed = seed
    scene.render.threads_mode = "FIXED"
    scene.render.threads = threads
    scene.render.resolution_x = width
    scene.render.resolution_y = height
    scene.render.resolution_percentage = 100
    scene.render.use_persistent_data = False
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.image_settings.exr_codec = "ZIP"

    results = {"startup_seconds": time.time() - START, "renders": [],
               "dropped_duplicate_faces": flat["dropped_duplicate_faces"], "until_seconds": until}

    # One render first, not recorded: the first render of a session pays for start-up (kernel
    # loading, ...) that the others do not; without it a 1-spp render takes longer than 2 spp.
    cycles.samples = 1
    scene.render.filepath = f"{prefix}-warmup.exr"
    t0 = time.time()
    bpy.ops.render.render(write_still=True)
    results["warmup_seconds"] = time.time() - t0

    def render(spp):
        cycles.samples = spp
        scene.render.filepath = f"{prefix}-{spp}spp.exr"
        t0, c0 = time.time(), time.process_time()
        bpy.ops.render.render(write_still=True)
        # cpu_seconds: the process's CPU time (all threads) over the render; on a shared
        # machine wall time says as much about the other users as about Cycles.
        results["renders"].append({"spp": spp, "seconds": time.time() - t0,
                                   "cpu_seconds": time.process_time() - c0, "image": scene.render.filepath})
        print(f"cycles: {spp} spp in {results['renders'][-1]['seconds']:.2f} s", flush=True)

    for spp in spps:
        render(spp)
    if until is not None:
        spp = max(spps)
        def spent(r):
            return r["cpu_seconds"] / threads if until_cpu else r["seconds"]

        while (not results["renders"] or spent(results["renders"][-1]) < until) and spp * 2 <= max_spp:
            spp *= 2
            render(spp)
    with open(prefix + ".json", "w", encoding="utf-8") as f:
        json.dump(results, f, indent=1)


if __name__ == "__main__":
    main(sys.argv[sys.argv.index("--") + 1:])
