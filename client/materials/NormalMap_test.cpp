// Normal maps (glTF normalTexture): the tangent frame from TANGENT or from the uvs, glTF's and
// OBJ's v, the bitangent's sign, degenerate frames, the below-surface fix and the conformance
// model NormalTangentMirrorTest.

#include "materials/NormalMap.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "scene/SceneLoader.h"
#include "scene/TestScenes.h"
#include "shading/Scattering.h"
#include "testing/TestScenes.h"
#include "tracing/EmbreeDevice.h"
#include "tracing/SceneGeometry.h"
#include "tracing/TraceableScene.h"
#include "util/TestPaths.h"

namespace igi {
namespace {

// A 1 x 1 RGB PNG of (166, 64, 230): tangent space (0.302, -0.498, 0.804), tilted toward +u
// and toward -v, so that a flipped green channel or a wrong bitangent shows.
const std::string kTexelPng(
    "\x89\x50\x4e\x47\x0d\x0a\x1a\x0a\x00\x00\x00\x0d\x49\x48\x44\x52\x00\x00\x00\x01\x00\x00"
    "\x00\x01\x08\x02\x00\x00\x00\x90\x77\x53\xde\x00\x00\x00\x0c\x49\x44\x41\x54\x78\x9c\x63"
    "\x58\xe6\xf0\x0c\x00\x03\x5c\x01\xcd\x95\x73\x0f\xb9\x00\x00\x00\x00\x49\x45\x4e\x44\xae"
    "\x42\x60\x82",
    69);
const glm::vec3 kTexel = glm::vec3(166.0f, 64.0f, 230.0f) / 255.0f;

// What the map must give on a plane whose +u runs along `t` and +v (up the image) along `b`,
// the plane facing +z.
glm::vec3 expectedNormal(glm::vec3 t, glm::vec3 b, float scale = 1.0f) {
    const glm::vec3 n = 2.0f * kTexel - 1.0f;
    return glm::normalize(scale * n.x * t + scale * n.y * b + n.z * glm::vec3(0, 0, 1));
}

void expectNear(glm::vec3 a, glm::vec3 b, float eps = 1e-4f) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

bool finite(glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// The hit of a ray straight down onto the plane z = 0 at (0.2, 0.3).
SurfacePoint hitOnPlane(const Scene& scene) {
    EmbreeDevice device;
    SceneGeometry geometry(device, scene);
    TraceableScene traceable(geometry);
    SurfacePoint hit;
    RayCounters counters;
    EXPECT_TRUE(traceable.intersect({0.2f, 0.3f, 2.0f}, {0, 0, -1}, 10.0f, hit, counters));
    EXPECT_NE(hit.material, nullptr);
    if (hit.material) {
        EXPECT_GE(hit.material->normalTexture, 0);
    }
    hit.material = nullptr;  // the scene is gone
    return hit;
}

// ---- glTF: the quad (-1, -1) .. (1, 1) at z = 0 facing +z, corners P0..P3 counter-clockwise
// from (-1, -1), with glTF's uvs (v down the image) and maybe TANGENT.

void appendFloats(std::string& bytes, const std::vector<float>& values) {
    const std::size_t at = bytes.size();
    bytes.resize(at + values.size() * sizeof(float));
    std::memcpy(bytes.data() + at, values.data(), values.size() * sizeof(float));
}

struct GltfQuad {
    std::vector<float> uvs;       // glTF's, 4 x 2
    std::vector<float> tangents;  // 4 x 4, or empty
    std::string node;             // more of the node, e.g. "\"scale\": [-1, 1, 1], "
    float scale = 1.0f;           // normalTexture.scale
};

Scene loadGltfQuad(const GltfQuad& q) {
    std::string bin;
    appendFloats(bin, {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0});  // 0: 48 bytes
    appendFloats(bin, {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1});      // 48: 48
    appendFloats(bin, q.uvs);                                     // 96: 32
    const std::uint32_t indices[6] = {0, 1, 2, 0, 2, 3};          // 128: 24
    bin.append(reinterpret_cast<const char*>(indices), sizeof indices);
    appendFloats(bin, q.tangents);  // 152: 64
    const bool tangents = !q.tangents.empty();
    const std::string gltf =
        R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{)" +
        q.node + R"("mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2)" +
        (tangents ? R"(, "TANGENT": 4)" : "") + R"(}, "indices": 3, "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.5},
                       "normalTexture": {"index": 0, "scale": )" +
        std::to_string(q.scale) + R"(}}],
        "textures": [{"source": 0}], "images": [{"uri": "n.png"}],
        "buffers": [{"uri": "q.bin", "byteLength": )" +
        std::to_string(bin.size()) + R"(}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 96, "byteLength": 32},
                        {"buffer": 0, "byteOffset": 128, "byteLength": 24})" +
        (tangents ? R"(, {"buffer": 0, "byteOffset": 152, "byteLength": 64})" : "") + R"(],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
             "min": [-1, -1, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5125, "count": 6, "type": "SCALAR"})" +
        (tangents ? R"(, {"bufferView": 4, "componentType": 5126, "count": 4, "type": "VEC4"})"
                  : "") +
        "]}";
    Scene scene = test::parseInline(
        R"({"meshes": [{"file": "q.gltf"}], "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0]}})",
        {{"q.gltf", gltf}, {"q.bin", bin}, {"n.png", kTexelPng}});
    EXPECT_EQ(scene.meshes.size(), 1u);
    if (!scene.meshes.empty()) {
        EXPECT_EQ(scene.meshes[0].tangents.size(),
                  tangents ? scene.meshes[0].positions.size() : 0u);
    }
    return scene;
}

const glm::vec3 kX(1, 0, 0), kY(0, 1, 0);

// glTF's uvs of an upright image: P0 (-1, -1) is the image's bottom left, uv (0, 1).
const std::vector<float> kUprightUvs = {0, 1, 1, 1, 1, 0, 0, 0};

TEST(NormalMap, GltfUprightImageTiltsAsTheTexelSays) {
    for (bool tangents : {false, true}) {
        SCOPED_TRACE(tangents ? "TANGENT" : "uv derivatives");
        GltfQuad q;
        q.uvs = kUprightUvs;
        if (tangents) q.tangents = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1};
        const SurfacePoint hit = hitOnPlane(loadGltfQuad(q));
        // +u right (+x), green up the image (+y).
        expectNear(hit.shadingNormal, expectedNormal(kX, kY));
        expectNear(hit.geometricNormal, {0, 0, 1});
    }
}

TEST(NormalMap, GltfScaleScalesTheTilt) {
    GltfQuad q;
    q.uvs = kUprightUvs;
    q.scale = 0.5f;
    expectNear(hitOnPlane(loadGltfQuad(q)).shadingNormal, expectedNormal(kX, kY, 0.5f));
}

TEST(NormalMap, GltfImageUpsideDownHasBitangentSignMinusOne) {
    for (bool tangents : {false, true}) {
        SCOPED_TRACE(tangents ? "TANGENT" : "uv derivatives");
        GltfQuad q;
        q.uvs = {0, 0, 1, 0, 1, 1, 0, 1};  // the image's top at the bottom: up is -y
        if (tangents) q.tangents = {1, 0, 0, -1, 1, 0, 0, -1, 1, 0, 0, -1, 1, 0, 0, -1};
        expectNear(hitOnPlane(loadGltfQuad(q)).shadingNormal, expectedNormal(kX, -kY));
    }
}

TEST(NormalMap, GltfImageMirroredInUHasBitangentSignMinusOne) {
    for (bool tangents : {false, true}) {
        SCOPED_TRACE(tangents ? "TANGENT" : "uv derivatives");
        GltfQuad q;
        q.uvs = {1, 1, 0, 1, 0, 0, 1, 0};  // +u toward -x, up the image +y
        if (tangents) q.tangents = {-1, 0, 0, -1, -1, 0, 0, -1, -1, 0, 0, -1, -1, 0, 0, -1};
        expectNear(hitOnPlane(loadGltfQuad(q)).shadingNormal, expectedNormal(-kX, kY));
    }
}

// A node that mirrors x: the image is mirrored with the quad, and the loader must turn the
// sign of TANGENT's w for the bitangent to stay up the image.
TEST(NormalMap, GltfMirroringNodeTurnsTheBitangentSign) {
    for (bool tangents : {false, true}) {
        SCOPED_TRACE(tangents ? "TANGENT" : "uv derivatives");
        GltfQuad q;
        q.uvs = kUprightUvs;
        q.node = R"("scale": [-1, 1, 1], )";
        if (tangents) q.tangents = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1};
        const Scene scene = loadGltfQuad(q);
        if (tangents) {
            EXPECT_EQ(scene.meshes[0].tangents[0], glm::vec4(-1, 0, 0, -1));
        }
        const SurfacePoint hit = hitOnPlane(scene);
        expectNear(hit.geometricNormal, {0, 0, 1});
        expectNear(hit.shadingNormal, expectedNormal(-kX, kY));
    }
}

// ---- Meshes built in code, uvs in OBJ's sense (v up the image).

Scene planeScene(const std::vector<glm::vec2>& uvs, const std::vector<glm::vec4>& tangents,
                 glm::vec3 normal = {0, 0, 1}) {
    Scene scene = testing::cornellBox(1.0f);
    scene.meshes.clear();
    Material m;
    m.name = "mapped";
    m.reflection = Reflection::Ggx;
    m.roughness = 0.5f;
    m.normalTexture = 0;
    scene.materials = {m};
    Texture t;
    t.path = "texel";
    t.width = t.height = 1;
    t.texels = {kTexel};
    t.average = t.minimum = kTexel;
    scene.textures = {t};
    Mesh mesh = testing::makeQuad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 0);
    mesh.normals.assign(4, glm::normalize(normal));
    mesh.uvs = uvs;
    mesh.tangents = tangents;
    scene.meshes = {mesh};
    return scene;
}

TEST(NormalMap, ObjUvsTiltAsTheTexelSays) {
    const std::vector<glm::vec2> uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (bool tangents : {false, true}) {
        SCOPED_TRACE(tangents ? "tangents" : "uv derivatives");
        const Scene scene = planeScene(
            uvs, tangents ? std::vector<glm::vec4>(4, {1, 0, 0, 1}) : std::vector<glm::vec4>());
        expectNear(hitOnPlane(scene).shadingNormal, expectedNormal(kX, kY));
    }
}

TEST(NormalMap, ObjUvsMirroredInUWithBitangentSignMinusOne) {
    const std::vector<glm::vec2> uvs = {{1, 0}, {0, 0}, {0, 1}, {1, 1}};
    for (bool tangents : {false, true}) {
        SCOPED_TRACE(tangents ? "tangents" : "uv derivatives");
        const Scene scene = planeScene(
            uvs, tangents ? std::vector<glm::vec4>(4, {-1, 0, 0, -1}) : std::vector<glm::vec4>());
        expectNear(hitOnPlane(scene).shadingNormal, expectedNormal(-kX, kY));
    }
}

// ---- Degenerate frames: the interpolated normal, finite.

TEST(NormalMap, DegenerateUvsKeepTheInterpolatedNormal) {
    const glm::vec3 n = glm::normalize(glm::vec3(0.1f, 0.2f, 1.0f));
    const std::vector<std::vector<glm::vec2>> cases = {
        std::vector<glm::vec2>(4, {0.5f, 0.5f}),         // one point
        {{0, 0}, {1, 1}, {2, 2}, {3, 3}},                // a line
        {{0, 0}, {1e-30f, 0}, {1e-30f, 1e-30f}, {0, 0}}  // almost nothing
    };
    for (const auto& uvs : cases) {
        for (bool parallelTangents : {false, true}) {
            const Scene scene =
                planeScene(uvs,
                           parallelTangents ? std::vector<glm::vec4>(4, glm::vec4(n, 1.0f))
                                            : std::vector<glm::vec4>(),
                           n);
            const SurfacePoint hit = hitOnPlane(scene);
            EXPECT_TRUE(finite(hit.shadingNormal));
            expectNear(hit.shadingNormal, n, 1e-6f);
        }
    }
}

TEST(NormalMap, FramesRefuseDegenerateInput) {
    normalmap::TangentFrame frame;
    const glm::vec3 n(0, 0, 1);
    EXPECT_FALSE(normalmap::frameFromTangent(n, {0, 0, 0}, 1, frame));
    EXPECT_FALSE(normalmap::frameFromTangent(n, {0, 0, 2}, 1, frame));
    EXPECT_FALSE(normalmap::frameFromTangent(n, {NAN, 0, 0}, 1, frame));
    const glm::vec3 p[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const glm::vec2 same[3] = {{0.3f, 0.3f}, {0.3f, 0.3f}, {0.3f, 0.3f}};
    EXPECT_FALSE(normalmap::frameFromUvs(n, p, same, frame));
    const glm::vec3 point[3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    const glm::vec2 uvs[3] = {{0, 0}, {1, 0}, {0, 1}};
    EXPECT_FALSE(normalmap::frameFromUvs(n, point, uvs, frame));
    // A zero texel (no normal at all) leaves n.
    ASSERT_TRUE(normalmap::frameFromUvs(n, p, uvs, frame));
    EXPECT_EQ(normalmap::perturb(n, frame, normalmap::tangentSpaceNormal(glm::vec3(0.5f), 1)), n);
}

// ---- Below the shading normal, above the geometric one.

TEST(NormalMap, ViewBelowTheShadingNormalIsBentAbove) {
    Material m;
    m.reflection = Reflection::Ggx;
    m.roughness = 0.3f;
    m.metallic = 1.0f;
    m.normalTexture = 0;
    SurfacePoint hit;
    hit.material = &m;
    hit.albedo = glm::vec3(0.9f);
    hit.roughness = m.roughness;
    hit.metallic = m.metallic;
    hit.geometricNormal = {0, 0, 1};
    hit.shadingNormal = glm::normalize(glm::vec3(1, 0, 1));          // tilted 45 degrees toward +x
    const glm::vec3 wo = glm::normalize(glm::vec3(-1, 0.2f, 0.4f));  // above ng, below ns
    ASSERT_LT(glm::dot(wo, hit.shadingNormal), 0.0f);
    const Lobes l = lobesAt(hit, wo);
    EXPECT_NEAR(glm::length(l.normal), 1.0f, 1e-5f);
    EXPECT_GT(glm::dot(l.normal, wo), 0.0f);
    EXPECT_GT(glm::dot(l.mirrorDirection, l.faceNormal), 0.0f);
    // Bent toward ng in the plane of ns and ng: still tilted toward +x, not past ng.
    EXPECT_NEAR(l.normal.y, 0.0f, 1e-6f);
    EXPECT_GT(l.normal.x, 0.0f);
    // The glossy lobe is not black, and samples above the surface.
    EXPECT_GT(maxComponent(l.brdf.glossy(l.mirrorDirection)), 0.0f);
    int sampled = 0;
    for (int i = 0; i < 64; ++i) {
        glm::vec3 direction, weight;
        if (sampleLobe(l, Lobe::Glossy, {(i + 0.5f) / 64.0f, (i * 37 % 64 + 0.5f) / 64.0f}, 0.5f,
                       direction, weight)) {
            ++sampled;
            EXPECT_TRUE(finite(weight));
        }
    }
    EXPECT_GT(sampled, 0);
    // A view whose mirror direction is above the surface keeps the normal exactly.
    EXPECT_EQ(lobesAt(hit, hit.shadingNormal).normal, hit.shadingNormal);
    EXPECT_EQ(lobesAt(hit, glm::normalize(glm::vec3(0.2f, 0.1f, 1))).normal, hit.shadingNormal);
}

TEST(NormalMap, EnsureValidReflectionLiftsTheMirrorDirection) {
    const glm::vec3 ng(0, 0, 1);
    for (float tilt : {0.3f, 1.0f, 3.0f, 30.0f}) {
        const glm::vec3 n = glm::normalize(glm::vec3(tilt, 0.1f, 1.0f));
        for (float z : {1e-4f, 0.01f, 0.1f, 0.5f}) {
            const glm::vec3 wo = glm::normalize(glm::vec3(-1.0f, 0.3f, z));
            const glm::vec3 bent = normalmap::ensureValidReflection(ng, wo, n);
            ASSERT_TRUE(finite(bent));
            EXPECT_NEAR(glm::length(bent), 1.0f, 1e-4f);
            const glm::vec3 r = 2.0f * glm::dot(bent, wo) * bent - wo;
            const float threshold = std::min(0.9f * glm::dot(ng, wo), 0.01f);
            EXPECT_GE(glm::dot(r, ng), threshold - 1e-4f) << tilt << " " << z;
            EXPECT_GE(glm::dot(bent, wo), 0.0f);
        }
    }
}

// ---- The glTF conformance model: TANGENT, mirrored uvs, its normal map.

TEST(NormalMap, NormalTangentMirrorTestLoadsAndRendersFinite) {
    const auto file = igi::testing::sharedScenesDir() / "gltf" / "NormalTangentMirrorTest" /
                      "glTF" / "NormalTangentMirrorTest.gltf";
    if (!std::filesystem::exists(file)) GTEST_SKIP() << "no " << file;
    Scene scene = loadSceneFile(file);
    ASSERT_EQ(scene.meshes.size(), 1u);
    const Mesh& mesh = scene.meshes[0];
    EXPECT_EQ(mesh.tangents.size(), mesh.positions.size());
    bool mapped = false;
    for (const Material& m : scene.materials) mapped = mapped || m.normalTexture >= 0;
    ASSERT_TRUE(mapped);
    scene.image = {48, 36, 0};
    testing::InProcessRenderer renderer(scene);
    const Image image = renderer.render(2);
    EXPECT_EQ(renderer.nonFiniteValues(), 0u);
    for (const glm::vec3& p : image.pixels) ASSERT_TRUE(finite(p));
    EXPECT_GT(testing::meanOf(image).x, 0.0);
    // The map shows: without it the image differs.
    Scene flat = scene;
    for (Material& m : flat.materials) m.normalTexture = -1;
    testing::InProcessRenderer flatRenderer(flat);
    const Image plain = flatRenderer.render(2);
    EXPECT_GT(testing::meanDifference(image, plain), 1e-3);
}

}  // namespace
}  // namespace igi
