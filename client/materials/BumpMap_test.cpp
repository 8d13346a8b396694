// MTL bump maps as height maps (BumpMap.h): the slope in texture space tilts the shading
// normal away from the rise, through the uvs' tangent frame (mirrored uvs tilt the other way);
// a height map of one constant slope shades a flat plane as the tilted plane; extreme scales
// stay above the geometric surface and finite; Dabrovic Sponza loads its bump maps as heights
// and renders.

#include "materials/BumpMap.h"

#include <cmath>
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "scene/SceneLoader.h"
#include "testing/TestScenes.h"
#include "tracing/EmbreeDevice.h"
#include "tracing/SceneGeometry.h"
#include "tracing/TraceableScene.h"
#include "util/TestPaths.h"

namespace igi {
namespace {

constexpr int kTexels = 256;
constexpr float kRise = 1.0f / 512.0f;  // height per texel along u

// A height ramp along u: kRise per texel (a grey map: every channel the height).
Texture ramp() {
    Texture t;
    t.path = "ramp";
    t.width = kTexels;
    t.height = 1;
    for (int i = 0; i < kTexels; ++i) t.texels.push_back(glm::vec3(kRise * float(i)));
    t.average = glm::vec3(kRise * 0.5f * float(kTexels - 1));
    return t;
}

void expectNear(glm::vec3 a, glm::vec3 b, float eps = 1e-4f) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

TEST(BumpMap, SlopePerTexelTimesTheScale) {
    const Texture t = ramp();
    // Away from the wrap: the ramp's slope, kRise per texel, against u; none along v.
    const glm::vec3 n = bumpmap::tangentSpaceNormal(t, {0.5f, 0.3f}, 8.0f);
    EXPECT_NEAR(n.x, -8.0f * kRise, 1e-5f);
    EXPECT_NEAR(n.y, 0.0f, 1e-6f);
    EXPECT_EQ(n.z, 1.0f);
    expectNear(bumpmap::tangentSpaceNormal(t, {0.5f, 0.3f}, 0.0f), {0, 0, 1}, 0.0f);
    EXPECT_FLOAT_EQ(bumpmap::height({0.3f, 0.6f, 0.9f}), 0.6f);
}

// The plane (-1, -1) .. (1, 1) at z = 0 facing +z with uvs `uvs` (the middle of the ramp, away
// from its wrap), bump-mapped with scale `scale`, under a point light.
Scene bumpedPlane(float scale, std::vector<glm::vec2> uvs) {
    Scene scene;
    scene.textures.push_back(ramp());
    Material m = testing::diffuse(glm::vec3(0.7f));
    m.name = "bumped";
    m.bumpTexture = 0;
    m.bumpScale = scale;
    scene.materials = {m};
    Mesh plane = testing::makeQuad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 0);
    plane.uvs = std::move(uvs);
    scene.meshes.push_back(plane);
    scene.punctualLights.push_back(pointLight("light", {-0.5f, 0.3f, 1.0f}, glm::vec3(1.0f)));
    scene.camera = {{0, -0.2f, 2.5f}, {0, 0, 0}, {0, 1, 0}, 40};
    scene.image = {24, 24, 0};
    scene.render.causticPhotons = 0;
    return scene;
}

const std::vector<glm::vec2> kMiddle = {{0.25f, 0}, {0.75f, 0}, {0.75f, 1}, {0.25f, 1}};

SurfacePoint hitOnPlane(const Scene& scene) {
    EmbreeDevice device;
    SceneGeometry geometry(device, scene);
    TraceableScene traceable(geometry);
    SurfacePoint hit;
    RayCounters counters;
    EXPECT_TRUE(traceable.intersect({0.2f, 0.3f, 2.0f}, {0, 0, -1}, 10.0f, hit, counters));
    hit.material = nullptr;  // the scene is gone
    return hit;
}

TEST(BumpMap, TiltsAwayFromTheRiseThroughTheUvFrame) {
    // u runs along +x: the height rises toward +x, so the normal leans toward -x by
    // atan(scale kRise), the slope being per texel whatever the plane's size.
    const float scale = 64.0f;
    const SurfacePoint hit = hitOnPlane(bumpedPlane(scale, kMiddle));
    expectNear(hit.geometricNormal, {0, 0, 1});
    expectNear(hit.shadingNormal, glm::normalize(glm::vec3(-scale * kRise, 0, 1)));
    // Mirrored uvs (u along -x): the rise is toward -x, the lean toward +x.
    const std::vector<glm::vec2> mirrored = {{0.75f, 0}, {0.25f, 0}, {0.25f, 1}, {0.75f, 1}};
    expectNear(hitOnPlane(bumpedPlane(scale, mirrored)).shadingNormal,
               glm::normalize(glm::vec3(scale * kRise, 0, 1)));
}

TEST(BumpMap, ExtremeScalesStayAboveTheSurfaceAndFinite) {
    for (float scale : {1e-4f, 1.0f, 1e4f, -1e4f}) {
        SCOPED_TRACE(scale);
        const SurfacePoint hit = hitOnPlane(bumpedPlane(scale, kMiddle));
        EXPECT_TRUE(std::isfinite(hit.shadingNormal.x) && std::isfinite(hit.shadingNormal.z));
        EXPECT_GE(hit.shadingNormal.z, 0.0f);
        EXPECT_NEAR(glm::length(hit.shadingNormal), 1.0f, 1e-5f);
        testing::InProcessRenderer renderer(bumpedPlane(scale, kMiddle));
        renderer.render(2);
        EXPECT_EQ(renderer.nonFiniteValues(), 0u);
    }
}

// A height map of one constant slope shades the flat plane as a plane whose vertex normals
// lean as the slope says (the same shading normal everywhere): the images agree.
TEST(BumpMap, ConstantSlopeShadesAsTheTiltedPlane) {
    const float scale = 256.0f;  // a lean of atan(0.5): 26.6 degrees
    const Scene bumped = bumpedPlane(scale, kMiddle);
    Scene tilted = bumped;
    tilted.materials[0].bumpTexture = -1;
    tilted.meshes[0].normals.assign(4, glm::normalize(glm::vec3(-scale * kRise, 0, 1)));
    testing::InProcessRenderer a(bumped), b(tilted);
    const Image ia = a.render(8), ib = b.render(8);
    Scene flat = bumped;
    flat.materials[0].bumpTexture = -1;
    testing::InProcessRenderer c(flat);
    const Image ic = c.render(8);
    const double same = testing::meanDifference(ia, ib), changed = testing::meanDifference(ia, ic);
    std::printf("bumped against tilted %.3g, against flat %.3g\n", same, changed);
    EXPECT_LT(same, 0.02 * changed);
}

TEST(BumpMap, DabrovicSponzaLoadsItsBumpMapsAsHeightsAndRenders) {
    const auto file = testing::sharedScenesDir() / "sponza-dabrovic" / "sponza.obj";
    if (!std::filesystem::exists(file)) GTEST_SKIP() << "no " << file;
    SceneLoadOptions options;
    options.allowOutsidePaths = true;
    Scene scene = loadSceneFile(file, nullptr, options);
    int bumped = 0, normalMapped = 0;
    for (const Material& m : scene.materials) {
        bumped += m.bumpTexture >= 0;
        normalMapped += m.normalTexture >= 0;
    }
    std::printf("sponza: %d materials with height maps, %d read as normal maps\n", bumped,
                normalMapped);
    EXPECT_GE(bumped, 5);
    EXPECT_EQ(normalMapped, 0);
    scene.image = {32, 24, 0};
    testing::InProcessRenderer renderer(scene);
    const Image image = renderer.render(1);
    EXPECT_EQ(renderer.nonFiniteValues(), 0u);
    EXPECT_GT(testing::meanOf(image).x, 0.0);
}

}  // namespace
}  // namespace igi
