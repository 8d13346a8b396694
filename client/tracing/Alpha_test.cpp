// Alpha cut-outs (client/tracing/AlphaCoverage.h): a checker mask casts a checker shadow for single
// rays, packets of 8 and 16 and both Embree layouts; BLEND's coverage converges to alpha and
// asks the same every time; cut-offs 0 and 1 render finite and bounded; the conformance model
// AlphaBlendModeTest loads and renders; opaque scenes keep one geometry per mesh.

#include "tracing/AlphaCoverage.h"

#include <cmath>
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "scene/SceneLoader.h"
#include "testing/TestScenes.h"
#include "tracing/EmbreeDevice.h"
#include "tracing/MovedInstances.h"
#include "tracing/SceneGeometry.h"
#include "tracing/TraceableScene.h"
#include "util/TestPaths.h"

namespace igi {
namespace {

constexpr int kChecker = 4;  // texels per side
const glm::vec3 kLight(0.0f, 0.0f, 3.0f);

// Alpha of checker texel (i, j), i along u, j along v: 0.9 where i + j is even, else 0.1.
float checkerAlpha(int i, int j) {
    return (i + j) % 2 == 0 ? 0.9f : 0.1f;
}

Texture checkerTexture() {
    Texture t;
    t.path = "checker";
    t.width = t.height = kChecker;
    t.texels.assign(kChecker * kChecker, glm::vec3(1.0f));
    t.average = glm::vec3(1.0f);
    t.minimum = glm::vec3(1.0f);
    t.alpha.resize(kChecker * kChecker);
    for (int j = 0; j < kChecker; ++j)
        for (int i = 0; i < kChecker; ++i)  // row 0 is the top of the image, v = 1
            t.alpha[(kChecker - 1 - j) * kChecker + i] = checkerAlpha(i, j);
    t.alphaMinimum = 0.1f;
    return t;
}

// A white ground (-2, -2) .. (2, 2) at z = 0 and, at z = 1, the plane (-1, -1) .. (1, 1) with
// uvs 0..1 of material 1 (both facing +z); a point light at kLight. Mesh 0 is the ground, 1 the
// plane. With `bigMesh`, a far sphere of 81920 triangles makes moved versions instanced.
Scene checkerScene(Material plane, bool bigMesh = false) {
    Scene scene;
    scene.textures.push_back(checkerTexture());
    scene.materials = {testing::diffuse(glm::vec3(0.8f)), plane};
    scene.meshes.push_back(testing::makeQuad({-2, -2, 0}, {4, 0, 0}, {0, 4, 0}, 0));
    Mesh p = testing::makeQuad({-1, -1, 1}, {2, 0, 0}, {0, 2, 0}, 1);
    p.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    scene.meshes.push_back(p);
    if (bigMesh) scene.meshes.push_back(testing::makeIcosphere(6, 1.0f, {0, 0, -40}, 0));
    scene.punctualLights.push_back(pointLight("light", kLight, glm::vec3(10.0f)));
    scene.camera = {{0, -6, 4}, {0, 0, 0.5f}, {0, 0, 1}, 50};
    scene.image = {32, 24, 0};
    return scene;
}

Material maskMaterial(float cutoff) {
    Material m = testing::diffuse(glm::vec3(0.7f));
    m.name = "mask";
    m.alphaMode = AlphaMode::Mask;
    m.alphaCutoff = cutoff;
    m.alphaTexture = 0;
    return m;
}

Material blendMaterial(float alpha, int texture = -1) {
    Material m = testing::diffuse(glm::vec3(0.7f));
    m.name = "blend";
    m.alphaMode = AlphaMode::Blend;
    m.alpha = alpha;
    m.alphaTexture = texture;
    return m;
}

// The ground point whose shadow ray to kLight crosses the plane at the centre of texel (i, j):
// the plane lies a third of the way up, so the ground point is 1.5 times as far out.
glm::vec3 groundUnderTexel(int i, int j) {
    const glm::vec2 uv((i + 0.5f) / kChecker, (j + 0.5f) / kChecker);
    const glm::vec2 onPlane = -1.0f + 2.0f * uv;
    return glm::vec3(1.5f * onPlane, 0.0f);
}

struct ShadowCase {
    glm::vec3 origin, direction;
    bool opaque;  ///< what the mask says of the texel the ray crosses
};

std::vector<ShadowCase> checkerShadowRays(float cutoff) {
    std::vector<ShadowCase> rays;
    for (int j = 0; j < kChecker; ++j)
        for (int i = 0; i < kChecker; ++i) {
            const glm::vec3 g = groundUnderTexel(i, j) + glm::vec3(0, 0, 1e-3f);
            rays.push_back({g, kLight - g, checkerAlpha(i, j) >= cutoff});
        }
    return rays;
}

// Every shadow ray alone, in packets of 8 and of 16: blocked exactly where the mask is opaque.
void expectCheckerShadow(const TraceableScene& traceable, float cutoff) {
    RayCounters counters;
    const auto cases = checkerShadowRays(cutoff);
    int blockedCount = 0;
    for (const ShadowCase& c : cases) {
        const bool blocked = traceable.occluded(c.origin, c.direction, 1.0f, counters);
        EXPECT_EQ(blocked, c.opaque) << c.origin.x << " " << c.origin.y;
        blockedCount += blocked;
    }
    EXPECT_EQ(blockedCount, int(cases.size()) / 2);  // half the texels are opaque
    for (int width : {8, 16}) {
        TraceableScene::ShadowRay rays[16];
        bool blocked[16];
        for (std::size_t start = 0; start < cases.size(); start += width) {
            const int count = std::min<int>(width, int(cases.size() - start));
            for (int k = 0; k < count; ++k)
                rays[k] = {cases[start + k].origin, cases[start + k].direction, 1.0f};
            TraceableScene& t = const_cast<TraceableScene&>(traceable);
            t.setPacketWidth(width);
            t.occludedPacket(rays, count, blocked, counters);
            for (int k = 0; k < count; ++k)
                EXPECT_EQ(blocked[k], cases[start + k].opaque) << "packet " << width;
        }
    }
}

TEST(Alpha, CheckerMaskCastsACheckerShadow) {
    const Scene scene = checkerScene(maskMaterial(0.5f));
    EmbreeDevice device;
    SceneGeometry geometry(device, scene);
    ASSERT_TRUE(geometry.hasCutOuts(1));
    EXPECT_FALSE(geometry.hasCutOuts(0));
    TraceableScene traceable(geometry);
    EXPECT_EQ(traceable.layout(), SceneLayout::Flat);
    expectCheckerShadow(traceable, 0.5f);
}

TEST(Alpha, EyeRaysSeeThroughTheHolesToTheGround) {
    const Scene scene = checkerScene(maskMaterial(0.5f));
    EmbreeDevice device;
    SceneGeometry geometry(device, scene);
    TraceableScene traceable(geometry);
    RayCounters counters;
    std::vector<glm::vec3> origins, directions;
    std::vector<float> tfar;
    std::vector<bool> opaque;
    for (int j = 0; j < kChecker; ++j)
        for (int i = 0; i < kChecker; ++i) {
            const glm::vec2 uv((i + 0.5f) / kChecker, (j + 0.5f) / kChecker);
            origins.push_back(glm::vec3(-1.0f + 2.0f * uv, 5.0f));
            directions.push_back({0, 0, -1});
            tfar.push_back(100.0f);
            opaque.push_back(checkerAlpha(i, j) >= 0.5f);
        }
    for (std::size_t k = 0; k < origins.size(); ++k) {
        SurfacePoint hit;
        ASSERT_TRUE(traceable.intersect(origins[k], directions[k], tfar[k], hit, counters));
        // Through a hole, the ground (mesh 0) at z = 0; else the plane, its own triangle.
        EXPECT_EQ(hit.mesh, opaque[k] ? 1u : 0u);
        EXPECT_NEAR(hit.position.z, opaque[k] ? 1.0f : 0.0f, 1e-5f);
        EXPECT_LT(hit.triangle, 2u);
        EXPECT_EQ(hit.material, &traceable.materials()[opaque[k] ? 1 : 0]);
    }
    for (int width : {8, 16}) {
        traceable.setPacketWidth(width);
        for (std::size_t start = 0; start < origins.size(); start += width) {
            SurfacePoint hits[16];
            bool found[16];
            traceable.intersectPacket(&origins[start], &directions[start], &tfar[start], width,
                                      hits, found, counters);
            for (int k = 0; k < width; ++k) {
                ASSERT_TRUE(found[k]);
                EXPECT_EQ(hits[k].mesh, opaque[start + k] ? 1u : 0u) << "packet " << width;
            }
        }
    }
}

TEST(Alpha, InstancedLayoutAndMovedObjectsCastTheSameShadow) {
    const Scene scene = checkerScene(maskMaterial(0.5f), true);
    EmbreeDevice device;
    SceneGeometry geometry(device, scene);
    SceneState moved = SceneState::of(scene);
    moved.transforms[2].translate = {0, 0, -1};  // the far sphere: the plane stays
    TraceableScene instanced(geometry, moved);
    ASSERT_EQ(instanced.layout(), SceneLayout::Instanced);
    expectCheckerShadow(instanced, 0.5f);
    // Hits report the mesh's own triangle in this layout too.
    SurfacePoint hit;
    RayCounters counters;
    ASSERT_TRUE(instanced.intersect({-0.75f, -0.75f, 5}, {0, 0, -1}, 100.0f, hit, counters));
    EXPECT_EQ(hit.mesh, 1u);
    // The plane moved: the scene of moved objects (before the move) sees the mask too.
    SceneState planeMoved = SceneState::of(scene);
    planeMoved.transforms[1].translate = {0, 0, 0.5f};
    MovedInstances instances(geometry, SceneState::of(scene), planeMoved);
    ASSERT_TRUE(instances.meshMoved(1));
    for (const ShadowCase& c : checkerShadowRays(0.5f))
        EXPECT_EQ(instances.occluded(true, c.origin, c.direction, 1.0f, counters), c.opaque);
}

TEST(Alpha, OpaqueScenesKeepOneGeometryPerMesh) {
    // An OPAQUE material (alpha ignored), a MASK whose cut-off no texel falls below and a BLEND
    // of alpha one: no cut-outs, no filter functions, primitive = triangle.
    Material opaque = maskMaterial(0.5f);
    opaque.alphaMode = AlphaMode::Opaque;
    for (const Material& m :
         {opaque, maskMaterial(0.1f), maskMaterial(0.0f), blendMaterial(1.0f)}) {
        const Scene scene = checkerScene(m);
        EXPECT_FALSE(hasCutOuts(m, scene.textures));
        EmbreeDevice device;
        SceneGeometry geometry(device, scene);
        EXPECT_FALSE(geometry.anyCutOuts());
        TraceableScene traceable(geometry);
        RayCounters counters;
        for (const ShadowCase& c : checkerShadowRays(0.5f))
            EXPECT_TRUE(traceable.occluded(c.origin, c.direction, 1.0f, counters));
    }
    EXPECT_TRUE(hasCutOuts(maskMaterial(0.1001f), {checkerTexture()}));
    EXPECT_TRUE(hasCutOuts(blendMaterial(0.999f), {}));
    EXPECT_TRUE(hasCutOuts(blendMaterial(1.0f, 0), {checkerTexture()}));
}

TEST(Alpha, CutoffExtremes) {
    // Cut-off 0: every texel stays (alpha >= 0); cut-off 1: every texel goes (alpha <= 0.9).
    EXPECT_TRUE(covers(maskMaterial(0.0f), 0.0f, 0.0f));
    EXPECT_TRUE(covers(maskMaterial(1.0f), 1.0f, 0.0f));
    EXPECT_FALSE(covers(maskMaterial(1.0f), 0.999f, 0.0f));
    EXPECT_FALSE(covers(blendMaterial(0.0f), 0.0f, 0.0f));  // random is in [0, 1)
    EXPECT_TRUE(covers(blendMaterial(1.0f), 1.0f, 0.99999994f));
    for (float cutoff : {0.0f, 1.0f}) {
        SCOPED_TRACE(cutoff);
        Scene scene = checkerScene(maskMaterial(cutoff));
        {
            EmbreeDevice device;
            SceneGeometry geometry(device, scene);
            TraceableScene traceable(geometry);
            RayCounters counters;
            for (const ShadowCase& c : checkerShadowRays(0.5f))
                EXPECT_EQ(traceable.occluded(c.origin, c.direction, 1.0f, counters),
                          cutoff == 0.0f);
        }
        testing::InProcessRenderer renderer(scene);
        const Image image = renderer.render(2);
        EXPECT_EQ(renderer.nonFiniteValues(), 0u);
        for (const glm::vec3& p : image.pixels) {
            ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
            ASSERT_GE(std::min({p.x, p.y, p.z}), 0.0f);
            ASSERT_LT(std::max({p.x, p.y, p.z}), 100.0f);
        }
        EXPECT_GT(testing::meanOf(image).x, 0.0);
    }
}

TEST(Alpha, BlendCoverageConvergesToAlpha) {
    for (float alpha : {0.0f, 0.25f, 0.5f, 0.9f, 1.0f}) {
        const Scene scene = checkerScene(blendMaterial(alpha));
        EmbreeDevice device;
        SceneGeometry geometry(device, scene);
        TraceableScene traceable(geometry);
        RayCounters counters;
        const int n = 20000;
        int blocked = 0;
        for (int k = 0; k < n; ++k) {
            // Shadow rays from spread ground points under the plane to the light.
            const float x = -1.2f + 2.4f * float((k * 7919) % 1000) / 1000.0f;
            const float y = -1.2f + 2.4f * float((k * 104729) % 997) / 997.0f;
            const glm::vec3 g(x, y, 1e-3f);
            blocked += traceable.occluded(g, kLight - g, 1.0f, counters);
        }
        const double fraction = double(blocked) / n;
        const double sigma = std::sqrt(alpha * (1.0 - alpha) / n);
        EXPECT_NEAR(fraction, alpha, 4.0 * sigma + 1e-9) << alpha;
    }
    // With the checker texture as alpha (0.9 and 0.1 by halves): the mean of the two.
    const Scene scene = checkerScene(blendMaterial(1.0f, 0));
    EmbreeDevice device;
    SceneGeometry geometry(device, scene);
    TraceableScene traceable(geometry);
    RayCounters counters;
    int blockedOpaque = 0, blockedClear = 0, rays = 0;
    for (int k = 0; k < 4000; ++k)
        for (const ShadowCase& c : checkerShadowRays(0.5f)) {
            // Each texel centre from slightly different ground points: a new hash each time.
            const glm::vec3 g =
                c.origin + glm::vec3(1e-5f * float(k % 64), 1e-5f * float(k / 64), 0);
            const bool b = traceable.occluded(g, kLight - g, 1.0f, counters);
            (c.opaque ? blockedOpaque : blockedClear) += b;
            ++rays;
        }
    EXPECT_NEAR(double(blockedOpaque) / (rays / 2), 0.9, 0.01);
    EXPECT_NEAR(double(blockedClear) / (rays / 2), 0.1, 0.01);
}

TEST(Alpha, BlendDecisionIsTheSameWhenAskedAgainAloneOrInPackets) {
    const Scene scene = checkerScene(blendMaterial(0.5f));
    EmbreeDevice device;
    SceneGeometry geometry(device, scene);
    TraceableScene traceable(geometry);
    RayCounters counters;
    std::vector<TraceableScene::ShadowRay> rays;
    for (int k = 0; k < 256; ++k) {
        const glm::vec3 g(-1.2f + 2.4f * float(k % 16) / 16.0f,
                          -1.2f + 2.4f * float(k / 16) / 16.0f, 1e-3f);
        rays.push_back({g, kLight - g, 1.0f});
    }
    std::vector<bool> single;
    for (const auto& r : rays)
        single.push_back(traceable.occluded(r.origin, r.direction, r.tfar, counters));
    int blocked = 0;
    for (std::size_t k = 0; k < rays.size(); ++k) {
        EXPECT_EQ(traceable.occluded(rays[k].origin, rays[k].direction, rays[k].tfar, counters),
                  single[k]);
        blocked += single[k];
    }
    EXPECT_GT(blocked, 64);  // neither all nor none
    EXPECT_LT(blocked, 192);
    for (int width : {8, 16}) {
        traceable.setPacketWidth(width);
        // Packets of every count up to the width, at every offset: Embree may split them.
        for (int count = 1; count <= width; ++count)
            for (std::size_t start = 0; start + count <= rays.size(); start += count) {
                bool b[16];
                traceable.occludedPacket(&rays[start], count, b, counters);
                for (int k = 0; k < count; ++k) ASSERT_EQ(b[k], single[start + k]) << width;
            }
    }
    // Eye rays (closest hit) in packets agree with single rays as well.
    std::vector<glm::vec3> origins, directions;
    std::vector<float> tfar;
    for (const auto& r : rays) {
        origins.push_back(r.origin + r.direction);  // from the light down to the ground
        directions.push_back(-r.direction);
        tfar.push_back(2.0f);
    }
    for (int width : {8, 16}) {
        traceable.setPacketWidth(width);
        for (std::size_t start = 0; start < rays.size(); start += width) {
            SurfacePoint hits[16];
            bool found[16];
            traceable.intersectPacket(&origins[start], &directions[start], &tfar[start], width,
                                      hits, found, counters);
            for (int k = 0; k < width; ++k) {
                SurfacePoint alone;
                ASSERT_TRUE(traceable.intersect(origins[start + k], directions[start + k],
                                                tfar[start + k], alone, counters));
                ASSERT_TRUE(found[k]);
                EXPECT_EQ(hits[k].mesh, alone.mesh);
            }
        }
    }
}

TEST(Alpha, CoverageRandomIsUniformAndDependsOnEveryInput) {
    const glm::vec3 o(0.1f, 0.2f, 0.3f), d(0, 0, 1);
    const float r = coverageRandom(o, d, 1, 2);
    EXPECT_GE(r, 0.0f);
    EXPECT_LT(r, 1.0f);
    EXPECT_EQ(coverageRandom(o, d, 1, 2), r);
    EXPECT_NE(coverageRandom(o, d, 1, 3), r);
    EXPECT_NE(coverageRandom(o, d, 2, 2), r);
    EXPECT_NE(coverageRandom(o + glm::vec3(0, 0, 1e-7f), d, 1, 2), r);
    EXPECT_NE(coverageRandom(o, glm::vec3(0, 1e-7f, 1), 1, 2), r);
    int below[4] = {};
    for (int k = 0; k < 40000; ++k)
        ++below[int(4.0f * coverageRandom(glm::vec3(float(k), 0, 0), d, 0, 0))];
    for (int q : below) EXPECT_NEAR(q, 10000, 400);
}

// ---- The glTF conformance model: OPAQUE, BLEND and MASK at cut-offs 0.25, 0.5, 0.75.

TEST(Alpha, AlphaBlendModeTestLoadsAndRenders) {
    const auto file = igi::testing::sharedScenesDir() / "gltf" / "AlphaBlendModeTest" / "glTF" /
                      "AlphaBlendModeTest.gltf";
    if (!std::filesystem::exists(file)) GTEST_SKIP() << "no " << file;
    Scene scene = loadSceneFile(file);
    int masks = 0, blends = 0;
    for (const Material& m : scene.materials) {
        masks += m.alphaMode == AlphaMode::Mask;
        blends += m.alphaMode == AlphaMode::Blend;
        if (m.alphaMode != AlphaMode::Opaque) {
            ASSERT_GE(m.alphaTexture, 0);
            EXPECT_FALSE(scene.textures[m.alphaTexture].alpha.empty());
            EXPECT_TRUE(hasCutOuts(m, scene.textures));
        }
    }
    EXPECT_EQ(masks, 3);
    EXPECT_EQ(blends, 1);
    scene.image = {64, 48, 0};
    {
        EmbreeDevice device;
        SceneGeometry geometry(device, scene);
        EXPECT_EQ(geometry.cutOutMeshes().empty(), false);
    }
    testing::InProcessRenderer renderer(scene);
    const Image image = renderer.render(2);
    EXPECT_EQ(renderer.nonFiniteValues(), 0u);
    for (const glm::vec3& p : image.pixels)
        ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
    EXPECT_GT(testing::meanOf(image).x, 0.0);
    // The cut-outs show: rendered all opaque, the image differs.
    Scene opaque = scene;
    for (Material& m : opaque.materials) m.alphaMode = AlphaMode::Opaque;
    testing::InProcessRenderer opaqueRenderer(opaque);
    const Image plain = opaqueRenderer.render(2);
    EXPECT_GT(testing::meanDifference(image, plain), 1e-3);
}

}  // namespace
}  // namespace igi
