#!/usr/bin/env bash
# Writes the seed corpus of fuzz_scene (fuzz/corpus/scene/) from the project's scene files and
# a few hand-made bad ones. A seed is one mode byte ('0' scene JSON, '1' OBJ, '2' MTL,
# '3' glTF: the file of fuzz/scene_bundle/ it replaces, see fuzz_scene.cpp) then the file.
# Usage: fuzz/make_scene_seeds.sh   (from anywhere; rewrites the folder)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$root/fuzz/corpus/scene"
rm -rf "$out"
mkdir -p "$out"

# seed NAME MODE FILE: MODE then the file's bytes.
seed() { { printf '%s' "$2"; cat "$3"; } >"$out/$1"; }
# text NAME MODE TEXT: MODE then TEXT.
text() { printf '%s%s' "$2" "$3" >"$out/$1"; }

# Real files. (scenes/cornell/sphere.obj is left out: at 75 KB it would raise libFuzzer's
# length limit for every input and slow the whole run down.)
seed cornell.json 0 "$root/scenes/cornell/cornell.json"
seed minimal.json 0 "$root/common/scene/testdata/minimal/scene.json"
seed gltf.json 0 "$root/common/scene/testdata/gltf/scene.json"
seed sponza.json 0 "$root/common/scene/testdata/sponza.json"
seed gltf-samples.json 0 "$root/common/scene/testdata/gltf-samples.json"
seed bundle.json 0 "$root/fuzz/scene_bundle/scene.json"
seed cornell-box.obj 1 "$root/scenes/cornell/box.obj"
seed cornell-room.obj 1 "$root/scenes/cornell/room.obj"
seed minimal-box.obj 1 "$root/common/scene/testdata/minimal/box.obj"
seed cornell-box.mtl 2 "$root/scenes/cornell/box.mtl"
seed cornell-room.mtl 2 "$root/scenes/cornell/room.mtl"
seed cornell-sphere.mtl 2 "$root/scenes/cornell/sphere.mtl"
seed minimal-box.mtl 2 "$root/common/scene/testdata/minimal/box.mtl"
seed triangle.gltf 3 "$root/fuzz/scene_bundle/triangle.gltf"

# glTF variants of the bundle's triangle.gltf that reach what it lacks: textures (an external
# image, the bundle's checker.ppm) and an external buffer, and the binary container (.glb).
python3 - "$root/fuzz/scene_bundle/triangle.gltf" "$out" <<'PY'
import base64, json, struct, sys
src, out = sys.argv[1], sys.argv[2]
gltf = json.load(open(src))
textured = json.loads(json.dumps(gltf))
textured["images"] = [{"uri": "checker.ppm"}]
textured["textures"] = [{"source": 0}]
textured["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
textured["materials"][2]["emissiveTexture"] = {"index": 0}
textured["buffers"].append({"byteLength": 132, "uri": "checker.ppm"})
with open(out + "/textured.gltf", "w") as f:
    f.write("3" + json.dumps(textured, separators=(",", ":")))
# GLB: the data: URI buffer moves to the BIN chunk.
data = base64.b64decode(gltf["buffers"][0]["uri"].split(",", 1)[1])
glb = json.loads(json.dumps(gltf))
glb["buffers"] = [{"byteLength": len(data)}]
text = json.dumps(glb, separators=(",", ":")).encode()
text += b" " * (-len(text) % 4)
data += b"\0" * (-len(data) % 4)
chunks = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(data), 0x004E4942) + data
with open(out + "/triangle.glb", "wb") as f:
    f.write(b"3" + b"glTF" + struct.pack("<II", 2, 12 + len(chunks)) + chunks)
PY

# Bad scene files: each should be refused with a SceneError.
text bad-syntax.json 0 $'{\n  "image": {"width": 12,,\n}'
text bad-top-level.json 0 '[1, 2]'
text bad-unknown-key.json 0 '{"meshes": [{"file": "box.obj", "transfrom": {}}]}'
text bad-overflow.json 0 '{"image": {"width": 10, "height": 10, "exposure": -1e999}}'
text bad-float-range.json 0 '{"lights": [{"type": "point", "position": [0, 1e300, 0], "intensity": 1}]}'
text bad-zero-scale.json 0 '{"meshes": [{"file": "box.obj", "transform": {"scale": [1, 0, 1]}}]}'
text bad-quad.json 0 '{"lights": [{"type": "quad", "corner": [0,0,0], "edge1": [1,0,0], "edge2": [2,0,0], "radiance": 1}]}'
text bad-material.json 0 '{"meshes": [{"file": "box.obj"}], "materials": {"floor": {"diffuse": [2, 0, 0], "texture": "CHECKER.PPM"}}}'
text bad-render.json 0 '{"render": {"interleave": [0, 99], "filter": 3, "seed": -1, "integrator": "mlt"}}'
text bad-camera.json 0 '{"camera": {"position": [0, 0, 0], "look_at": [0, 0, 0], "fov_y": 180}}'
text bad-mesh-path.json 0 '{"meshes": [{"file": "../../etc/passwd.obj"}, {"file": "x.ply"}]}'
text bad-nesting.json 0 '{"meshes": [[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]}'
# Bad OBJ files.
text bad-index.obj 1 $'v 0 0 0\nv 1 0 0\nf 1 2 3\n'
text bad-negative-index.obj 1 $'v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\nf 0 1 2\n'
text bad-nan.obj 1 $'v 0 nan 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n'
text bad-usemtl.obj 1 $'mtllib box.mtl missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nusemtl nothere\nf 1/1/1 2/1/1 3/1/1\n'
text polygon.obj 1 $'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0.5 2 0\nv 0 1 0\nvn 0 0 0\nf 1//1 2//1 3//1 4//1 5//1\nl 1 2\np 3\n'
# Bad MTL files.
text bad-texture.mtl 2 $'newmtl floor\nKd 0.5 0.5 0.5\nmap_Kd nothere.png\n'
text bad-values.mtl 2 $'newmtl floor\nKd -1 2 nan\nKs 1 1 1\nNs -5\nNi 0\nd 0.5\nillum 7\nKe inf 0 0\nnewmtl lamp\nmap_Kd box.obj\n'
text case-texture.mtl 2 $'newmtl floor\nKd 0.5 0.5 0.5\nmap_Kd Checker.PPM\n\nnewmtl lamp\nKe 1 1 1\n'
# Bad glTF files.
text bad-truncated.gltf 3 '{"asset": {"version": "2.0"}, "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}]'
text bad-accessor.gltf 3 '{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0,"children":[0]}],"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":0}]}],"buffers":[{"byteLength":12,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAIA/"}],"bufferViews":[{"buffer":0,"byteOffset":8,"byteLength":100}],"accessors":[{"bufferView":0,"componentType":5126,"count":1000,"type":"VEC3"}]}'
# A binary glTF header announcing 2 GB (bytes with NULs: written by printf's own escapes).
printf '3glTF\002\000\000\000\377\377\377\177' >"$out/bad-binary.gltf"

echo "$(ls "$out" | wc -l) seeds in $out"
