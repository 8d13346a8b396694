// Hostile sizes are refused with a clear error before anything of that size is allocated:
// files, scene files, meshes, lights, materials, triangles, vertices, textures, glTF objects.
// Most tests inject a small limit; some check a default on a file that only claims a size
// (a sparse file, an image header without pixels, a glTF count without data).

#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "util/ExpectContains.h"

#include "scene/SceneLoader.h"
#include "scene/TestScenes.h"
#include "scene/TextureLoader.h"

namespace igi {
namespace {

namespace fs = std::filesystem;

using test::kTriangle;
constexpr const char* kCamera = R"("camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]})";

using Files = std::map<std::string, std::string>;

// The SceneError of parsing `json` (as a client would, from memory) within `limits`, or "".
std::string errorOf(const std::string& json, Files files, const SceneLimits& limits = {}) {
    BundleFileSource source(std::move(files));
    try {
        parseScene(json, "inline.json", source, limits);
    } catch (const SceneError& e) {
        return e.what();
    }
    return "";
}

std::string meshes(const std::vector<std::string>& files) {
    std::string json = std::string("{") + kCamera + R"(, "meshes": [)";
    for (std::size_t i = 0; i < files.size(); ++i)
        json += (i ? ", " : "") + std::string(R"({"file": ")") + files[i] + R"("})";
    return json + "]}";
}

std::string readTestFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    return std::move(bytes).str();
}

std::string triangleGltf() {
    return readTestFile(test::testdataDir() / "gltf" / "triangle.gltf");
}

// A folder of its own, removed at the end of the test.
class TempDir {
  public:
    TempDir() {
        static std::atomic<int> counter{0};
        path_ = fs::temp_directory_path() /
                ("igi-limits-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
        fs::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    const fs::path& path() const { return path_; }
    void write(const std::string& name, const std::string& text) const {
        std::ofstream(path_ / name, std::ios::binary) << text;
    }
    // A file that claims `size` bytes without using the disk for them.
    void sparse(const std::string& name, std::uintmax_t size) const {
        std::ofstream(path_ / name, std::ios::binary).put('x');
        fs::resize_file(path_ / name, size);
    }

  private:
    fs::path path_;
};

// ---- Files --------------------------------------------------------------------------------

TEST(FileLimits, FileOverTwoGibIsRefusedBeforeReading) {
    TempDir dir;
    dir.sparse("big.obj", 2 * kGiB + 1);
    DiskFileSource disk(dir.path());
    EXPECT_CONTAINS(test::sceneErrorOf([&] { disk.read("big.obj"); }),
                    "big.obj: file is 2147483649 bytes, over the limit of 2147483648 bytes");
    EXPECT_TRUE(disk.filesRead().empty());
}

TEST(FileLimits, FileLimitIsAParameter) {
    TempDir dir;
    dir.write("twenty.obj", std::string(20, '#'));
    SceneLoadOptions options;
    options.limits.maxFileBytes = 19;
    DiskFileSource small(dir.path(), options);
    EXPECT_CONTAINS(test::sceneErrorOf([&] { small.read("twenty.obj"); }),
                    "file is 20 bytes, over the limit of 19 bytes");
    options.limits.maxFileBytes = 20;
    DiskFileSource enough(dir.path(), options);
    EXPECT_EQ(enough.read("twenty.obj").size(), 20u);
}

TEST(FileLimits, SceneFileOver64MibIsRefused) {
    TempDir dir;
    dir.sparse("scene.json", 64 * kMiB + 1);
    EXPECT_CONTAINS(test::sceneErrorOf([&] { loadSceneFile(dir.path() / "scene.json"); }),
                    "scene.json: file is 67108865 bytes, over the limit of 67108864 bytes");
}

TEST(FileLimits, AllFilesOfASceneTogether) {
    TempDir dir;
    dir.write("a.obj", std::string(20, '#'));
    dir.write("b.obj", std::string(20, '#'));
    SceneLoadOptions options;
    options.limits.maxTotalBytes = 30;
    DiskFileSource disk(dir.path(), options);
    disk.read("a.obj");
    disk.read("a.obj");  // read once, counted once
    EXPECT_CONTAINS(
        test::sceneErrorOf([&] { disk.read("b.obj"); }),
        "b.obj: 20 more bytes would exceed the limit of 30 read per scene (20 already)");
}

TEST(FileLimits, OnlyRegularFilesAreRead) {
    EXPECT_CONTAINS(test::sceneErrorOf([] { readRegularFile("/dev/zero", 100, "zero.obj"); }),
                    "zero.obj: cannot read file: not a regular file");
}

TEST(FileLimits, BundlesAreHeldToTheSameSizes) {
    SceneBundle bundle;
    bundle.sceneName = "scene.json";
    bundle.sceneText = std::string("{") + kCamera + "}";
    SceneLimits limits;
    limits.maxSceneFileBytes = bundle.sceneText.size() - 1;
    EXPECT_CONTAINS(test::sceneErrorOf([&] { loadSceneBundle(bundle, limits); }),
                    "scene.json: scene file is");
    limits = SceneLimits();
    limits.maxFileBytes = 3;
    bundle.files = {{"a.obj", "four"}};
    EXPECT_CONTAINS(test::sceneErrorOf([&] { loadSceneBundle(bundle, limits); }),
                    "a.obj: file is 4 bytes, over the limit of 3 bytes");
}

// ---- Counts in the scene file ------------------------------------------------------------

std::string manyEmptyObjects(std::size_t n) {
    std::string list;
    for (std::size_t i = 0; i < n; ++i) list += i ? ",{}" : "{}";
    return list;
}

TEST(SceneLimits, MoreThan100000MeshesAreRefusedBeforeAnyIsRead) {
    const std::string json = R"({"meshes": [)" + manyEmptyObjects(100001) + "]}";
    EXPECT_CONTAINS(errorOf(json, {}),
                    "inline.json: /meshes: 100001 meshes, over the limit of 100000");
    SceneLimits limits;
    limits.maxMeshes = 1;
    EXPECT_CONTAINS(errorOf(meshes({"a.obj", "a.obj"}), {{"a.obj", kTriangle}}, limits),
                    "/meshes: 2 meshes, over the limit of 1");
    EXPECT_EQ(errorOf(meshes({"a.obj"}), {{"a.obj", kTriangle}}, limits), "");
}

TEST(SceneLimits, MoreThan100000LightsAreRefused) {
    const std::string json = R"({"lights": [)" + manyEmptyObjects(100001) + "]}";
    EXPECT_CONTAINS(errorOf(json, {}),
                    "inline.json: /lights: 100001 lights would exceed the limit of 100000 per "
                    "scene (0 from glTF files)");
}

TEST(SceneLimits, GltfLightsCountTowardsTheLightLimit) {
    SceneLimits limits;
    limits.maxLights = 3;  // the file has three
    const std::string json = std::string("{") + kCamera +
                             R"(, "meshes": [{"file": "t.gltf"}],
        "lights": [{"type": "point", "position": [0, 0, 0], "intensity": 1}]})";
    EXPECT_CONTAINS(errorOf(json, {{"t.gltf", triangleGltf()}}, limits),
                    "/lights: 1 lights would exceed the limit of 3 per scene (3 from glTF files)");
    limits.maxLights = 0;
    EXPECT_CONTAINS(errorOf(meshes({"t.gltf"}), {{"t.gltf", triangleGltf()}}, limits),
                    "/meshes/0/file: its 3 lights would exceed the limit of 0 lights per scene");
}

TEST(SceneLimits, MtlMaterialsAreCountedBeforeTinyobjloaderReadsThem) {
    SceneLimits limits;
    limits.maxMaterials = 2;
    const Files files{{"m.obj", "mtllib m.mtl\n" + std::string(kTriangle)},
                      {"m.mtl", "newmtl a\nnewmtl b\nnewmtl c\n"}};
    EXPECT_CONTAINS(errorOf(meshes({"m.obj"}), files, limits),
                    "m.obj:1: material library 'm.mtl': 3 more materials would exceed the limit "
                    "of 2 per scene (0 already)");
    limits.maxMaterials = 3;
    EXPECT_EQ(errorOf(meshes({"m.obj"}), files, limits), "");
}

TEST(SceneLimits, GltfMaterialsAreCountedBeforeTinygltfReadsThem) {
    SceneLimits limits;
    limits.maxMaterials = 2;  // triangle.gltf has 3
    EXPECT_CONTAINS(errorOf(meshes({"t.gltf"}), {{"t.gltf", triangleGltf()}}, limits),
                    "t.gltf: 3 more materials would exceed the limit of 2 per scene (0 already)");
}

TEST(SceneLimits, DeeplyNestedSceneJsonIsAnErrorNotACrash) {
    const std::size_t depth = 200000;
    const std::string json =
        R"({"meshes": )" + std::string(depth, '[') + std::string(depth, ']') + "}";
    EXPECT_NE(errorOf(json, {}), "");
}

// ---- OBJ ------------------------------------------------------------------------------------

TEST(ObjLimits, TrianglesPerSceneAreCountedBeforeParsing) {
    SceneLimits limits;
    limits.maxTriangles = 1;
    const std::string quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
    EXPECT_CONTAINS(errorOf(meshes({"q.obj"}), {{"q.obj", quad}}, limits),
                    "q.obj: 2 more triangles would exceed the limit of 1 per scene (0 already)");
    // Across files.
    EXPECT_CONTAINS(
        errorOf(meshes({"a.obj", "b.obj"}), {{"a.obj", kTriangle}, {"b.obj", kTriangle}}, limits),
        "b.obj: 1 more triangles would exceed the limit of 1 per scene (1 already)");
    // Lines end at a lone \r too, as tinyobjloader reads them.
    const std::string crOnly = "v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 3\rf 1 3 2\r";
    EXPECT_CONTAINS(errorOf(meshes({"cr.obj"}), {{"cr.obj", crOnly}}, limits),
                    "cr.obj: 2 more triangles would exceed the limit of 1 per scene");
}

TEST(ObjLimits, VerticesPerScene) {
    SceneLimits limits;
    limits.maxVertices = 2;
    EXPECT_CONTAINS(errorOf(meshes({"a.obj"}), {{"a.obj", kTriangle}}, limits),
                    "a.obj: 3 more vertices would exceed the limit of 2 per scene (0 already)");
}

TEST(ObjLimits, FaceWithMoreThan256CornersNamesTheLine) {
    std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf";
    for (int i = 0; i < 257; ++i) {
        obj += ' ';
        obj += std::to_string(i % 3 + 1);
    }
    obj += "\n";
    EXPECT_CONTAINS(errorOf(meshes({"a.obj"}), {{"a.obj", obj}}),
                    "a.obj:4: face has 257 corners, over the limit of 256");
}

TEST(ObjLimits, GroupsPerFile) {
    SceneLimits limits;
    limits.maxObjGroups = 1;
    const std::string obj = "o a\n" + std::string(kTriangle) + "g b\nf 1 2 3\n";
    EXPECT_CONTAINS(errorOf(meshes({"a.obj"}), {{"a.obj", obj}}, limits),
                    "a.obj: 2 o and g statements, over the limit of 1 per OBJ file");
}

TEST(ObjLimits, AbsurdIndicesAreRefused) {
    // tinyobjloader reads indices as int: 4294967299 would wrap around to a valid 3.
    for (const char* face : {"f 1 2 4294967299\n", "f 1 2 -99999999999\n",
                             "f 1 2 99999999999999999999\n", "f 1 2 2147483647\n"}) {
        SCOPED_TRACE(face);
        const std::string what = errorOf(
            meshes({"a.obj"}), {{"a.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n" + std::string(face)}});
        EXPECT_CONTAINS(what, "a.obj:4: ");
    }
}

// ---- Textures -------------------------------------------------------------------------------

TEST(TextureLimits, HeaderClaimingHugeSizeIsRefusedWithoutReadingPixels) {
    // Headers only: reading the pixels would fail with "cannot decode" instead.
    EXPECT_CONTAINS(
        test::sceneErrorOf([] { decodeTexture("huge.ppm", "P6\n100000 100000\n255\n"); }),
        "huge.ppm: unsupported image size 100000 x 100000");
    EXPECT_CONTAINS(test::sceneErrorOf([] { decodeTexture("big.ppm", "P6\n10000 10000\n255\n"); }),
                    "big.ppm: image is 10000 x 10000 pixels, over the limit of 67108864 pixels "
                    "per texture");
    TextureLimits limits;
    limits.maxPixels = 3;
    EXPECT_CONTAINS(test::sceneErrorOf([&] {
                        decodeTexture("t.ppm", "P3\n2 2\n255\n" + std::string(12 * 2, ' '), limits);
                    }),
                    "t.ppm: image is 2 x 2 pixels, over the limit of 3 pixels per texture");
}

TEST(TextureLimits, HugeTextureInAnMtlNamesTheLine) {
    const Files files{{"m.obj", "mtllib m.mtl\nusemtl a\n" + std::string(kTriangle)},
                      {"m.mtl", "newmtl a\nKd 1 1 1\nmap_Kd big.ppm\n"},
                      {"big.ppm", "P6\n10000 10000\n255\n"}};
    EXPECT_CONTAINS(errorOf(meshes({"m.obj"}), files),
                    "m.mtl:3: big.ppm: image is 10000 x 10000 pixels, over the limit");
}

TEST(TextureLimits, TexturePixelsPerScene) {
    const std::string checker = readTestFile(test::testdataDir() / "minimal" / "checker.ppm");
    const Files files{{"m.obj", "mtllib m.mtl\nusemtl a\n" + std::string(kTriangle)},
                      {"m.mtl", "newmtl a\nmap_Kd a.ppm\nnewmtl b\nmap_Kd b.ppm\n"},
                      {"a.ppm", checker},
                      {"b.ppm", checker}};
    SceneLimits limits;
    limits.maxTotalTexturePixels = 7;  // two 2 x 2 textures are 8
    EXPECT_CONTAINS(errorOf(meshes({"m.obj"}), files, limits),
                    "m.mtl:4: b.ppm: image is 2 x 2 pixels: 4 more texture pixels would exceed "
                    "the limit of 7 per scene (4 already)");
    limits.maxTotalTexturePixels = 8;
    EXPECT_EQ(errorOf(meshes({"m.obj"}), files, limits), "");
}

// ---- glTF -----------------------------------------------------------------------------------

// triangle.gltf with `from` replaced by `to` (which must occur).
std::string editedGltf(const std::string& from, const std::string& to) {
    std::string text = triangleGltf();
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

constexpr const char* kFirstAccessor = R"("componentType": 5126,
   "count": 3,
   "type": "VEC3",
   "min")";

std::string gltfError(const std::string& gltf, const SceneLimits& limits = {}) {
    return errorOf(meshes({"t.gltf"}), {{"t.gltf", gltf}}, limits);
}

TEST(GltfLimits, AccessorCountIsCheckedAgainstItsBufferBeforeAllocating) {
    // tinygltf does not check: a count of 10^15 would allocate 12 PB of floats.
    const std::string huge = editedGltf(kFirstAccessor, R"("componentType": 5126,
   "count": 1000000000000000, "type": "VEC3", "min")");
    EXPECT_CONTAINS(gltfError(huge),
                    "t.gltf: /accessors/0: count 1000000000000000 is over the limit of 150000000");
    // The indices: 1000 unsigned shorts in a 6-byte buffer view.
    const std::string pastTheEnd = editedGltf(R"("componentType": 5123,
   "count": 3,)",
                                              R"("componentType": 5123, "count": 1000,)");
    EXPECT_CONTAINS(gltfError(pastTheEnd),
                    "t.gltf: /accessors/3: accessor reaches past the end of its buffer");
}

TEST(GltfLimits, OffsetsNearTwoToThe64DoNotWrapAround) {
    const std::string offset = editedGltf(R"("bufferView": 0,
   "byteOffset": 0,
   "componentType": 5126,
   "count": 3)",
                                          R"("bufferView": 0,
   "byteOffset": 18446744073709551600, "componentType": 5126, "count": 3)");
    EXPECT_CONTAINS(gltfError(offset), "/accessors/0: accessor reaches past the end of its buffer");
    const std::string view = editedGltf(R"("byteOffset": 0,
   "byteLength": 72)",
                                        R"("byteOffset": 18446744073709551600, "byteLength": 72)");
    EXPECT_CONTAINS(gltfError(view),
                    "/accessors/0: its buffer view reaches past the end of its buffer");
}

TEST(GltfLimits, ImageBufferViewMustLieInsideItsBuffer) {
    // tinygltf 2.7 would copy 1000 bytes out of the 104-byte buffer.
    std::string gltf = editedGltf(R"("buffers": [)",
                                  R"("images": [{"bufferView": 3, "mimeType": "image/png"}],
 "buffers": [)");
    const std::string lastView = R"({
   "buffer": 0,
   "byteOffset": 96,
   "byteLength": 6
  })";
    ASSERT_NE(gltf.find(lastView), std::string::npos);
    gltf.replace(gltf.find(lastView), lastView.size(),
                 lastView + R"(, {"buffer": 0, "byteOffset": 100, "byteLength": 1000})");
    EXPECT_CONTAINS(gltfError(gltf),
                    "t.gltf: /images/0: its buffer view reaches past the end of its buffer");
}

TEST(GltfLimits, NodeReachedTwiceIsRefused) {
    // Node 0 is a root of the scene and a child of node 2: with such sharing, the paths
    // through a graph can double at every level.
    const std::string gltf = editedGltf(R"("children": [
    1
   ])",
                                        R"("children": [1, 0])");
    EXPECT_CONTAINS(gltfError(gltf),
                    "t.gltf: /nodes/0: node is reached twice (glTF nodes must form trees)");
}

TEST(GltfLimits, TrianglesAndVerticesPerScene) {
    SceneLimits limits;
    limits.maxTriangles = 2;  // three primitives of one triangle each
    EXPECT_CONTAINS(gltfError(triangleGltf(), limits),
                    "t.gltf: /meshes/0/primitives/2: 1 more triangles would exceed the limit of 2 "
                    "per scene (2 already)");
    limits = SceneLimits();
    limits.maxVertices = 8;
    EXPECT_CONTAINS(gltfError(triangleGltf(), limits),
                    "/meshes/0/primitives/2: 3 more vertices would exceed the limit of 8");
}

TEST(GltfLimits, ObjectsAndJsonValuesPerFile) {
    SceneLimits limits;
    limits.maxGltfObjects = 10;
    EXPECT_CONTAINS(gltfError(triangleGltf(), limits),
                    "objects (nodes, meshes, primitives, accessors, ...), over the limit of 10");
    limits = SceneLimits();
    limits.maxGltfJsonValues = 10;
    EXPECT_CONTAINS(gltfError(triangleGltf(), limits),
                    "t.gltf: more than 10 JSON values, over the limit per glTF file");
}

TEST(GltfLimits, DeeplyNestedExtrasAreRefusedNotRecursedInto) {
    const std::size_t depth = 100000;
    const std::string gltf = R"({"asset": {"version": "2.0"}, "extras": )" +
                             std::string(depth, '[') + std::string(depth, ']') + "}";
    EXPECT_CONTAINS(gltfError(gltf), "t.gltf: JSON nested deeper than 128 levels");
}

// A binary glTF: header, JSON chunk, BIN chunk.
std::string glb(std::string json, const std::string& bin) {
    while (json.size() % 4) json += ' ';
    auto u32 = [](std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
    const std::uint32_t length = 12 + 8 + json.size() + 8 + bin.size();
    return "glTF" + u32(2) + u32(length) + u32(json.size()) + "JSON" + json + u32(bin.size()) +
           std::string("BIN\0", 4) + bin;
}

TEST(GltfLimits, GlbBinaryChunkCopiedIntoManyBuffersIsRefused) {
    // tinygltf copies the binary chunk into every buffer without a uri.
    const std::string json = R"({"asset": {"version": "2.0"}, "buffers": [
        {"byteLength": 64}, {"byteLength": 64}, {"byteLength": 64}]})";
    SceneLimits limits;
    limits.maxTotalBytes = 100;
    EXPECT_CONTAINS(
        errorOf(meshes({"t.glb"}), {{"t.glb", glb(json, std::string(64, 'b'))}}, limits),
        "t.glb: /buffers/1: 64 more bytes of buffers and images would exceed the limit "
        "of 100 per glTF file (64 already)");
}

TEST(GltfLimits, ExternalFileNamedByManyBuffersIsRefused) {
    const std::string json = std::string("{") + R"("asset": {"version": "2.0"}, "buffers": [
        {"byteLength": 36, "uri": "t.bin"}, {"byteLength": 36, "uri": "t.bin"},
        {"byteLength": 36, "uri": "t.bin"}]})";
    SceneLimits limits;
    limits.maxTotalBytes = 100;
    EXPECT_CONTAINS(
        errorOf(meshes({"t.gltf"}), {{"t.gltf", json}, {"t.bin", std::string(36, 'b')}}, limits),
        "t.gltf: cannot load glTF: t.bin: 36 more bytes of buffers and images would "
        "exceed the limit of 100 per glTF file (72 already)");
}

TEST(GltfLimits, MalformedGlbHeaderIsAnError) {
    std::string bytes = glb(R"({"asset": {"version": "2.0"}})", "");
    bytes[12] = '\xff';  // a JSON chunk longer than the file
    EXPECT_CONTAINS(errorOf(meshes({"t.glb"}), {{"t.glb", bytes}}),
                    "t.glb: invalid glTF binary: bad JSON chunk header");
}

}  // namespace
}  // namespace igi
