// The environment as a light (issue 35): its sampler, the furnace, its orientation through a
// mirror, a map with one texel 1e6 times the rest, and IGI against the path tracer under a map.

#include "tracing/EnvironmentMap.h"

#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "math/Color.h"
#include "math/Warp.h"
#include "sampling/Sobol.h"
#include "testing/TestScenes.h"

namespace igi {
namespace {

using testing::InProcessRenderer;

// A w x h map of `base` with one texel (x, y) of `peak`.
Texture oneBrightTexel(int w, int h, int x, int y, float base, float peak) {
    Texture t;
    t.path = "test.exr";
    t.width = w;
    t.height = h;
    t.texels.assign(std::size_t(w) * std::size_t(h), glm::vec3(base));
    t.texels[std::size_t(y) * std::size_t(w) + std::size_t(x)] = glm::vec3(peak);
    return t;
}

// A smooth sky: bright above, a warm band near the horizon, dim below.
Texture smoothSky(int w, int h) {
    Texture t;
    t.path = "sky.exr";
    t.width = w;
    t.height = h;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float v = (y + 0.5f) / float(h), u = (x + 0.5f) / float(w);
            const float band = std::exp(-std::pow((v - 0.5f) * 8.0f, 2.0f));
            t.texels.push_back(glm::vec3(0.2f + 2.0f * (1.0f - v) + band * (1.0f + u),
                                         0.3f + 1.5f * (1.0f - v) + 0.5f * band, 0.1f + 1.0f - v));
        }
    return t;
}

TEST(EnvironmentMap, DensityIntegratesToOneAndMatchesItsSampler) {
    const std::vector<Texture> textures = {smoothSky(32, 16)};
    Environment e;
    e.radiance = glm::vec3(1.0f);
    e.texture = 0;
    e.rotateDeg = 30.0f;
    const EnvironmentMap map(e, textures);
    // E[pdf(w) / uniform pdf] over uniform directions is the integral of the pdf.
    const int n = 1 << 16;
    double integral = 0, ratio = 0;
    int elsewhere = 0;  // samples whose direction rounds into a neighbouring texel
    for (int i = 0; i < n; ++i) {
        const glm::vec2 u(Sobol::scrambled(std::uint32_t(i), 0, 0),
                          Sobol::scrambled(std::uint32_t(i), 1, 0));
        integral += map.pdf(squareToUniformSphere(u)) * 4.0 * kPi;
        // The sampler's direction has the density pdf() gives it, and the radiance there.
        const EnvironmentMap::Sample s = map.sample(u);
        ratio += s.pdf / map.pdf(s.toSky);
        elsewhere += s.radiance != map.radiance(s.toSky);
    }
    EXPECT_LT(elsewhere, n / 1000);
    EXPECT_NEAR(integral / n, 1.0, 2e-3);
    EXPECT_NEAR(ratio / n, 1.0, 1e-3);
}

TEST(EnvironmentMap, AOneInAMillionTexelGetsItsShareOfTheSamples) {
    const int w = 64, h = 32;
    const std::vector<Texture> textures = {oneBrightTexel(w, h, 40, 9, 1.0f, 1e6f)};
    Environment e;
    e.radiance = glm::vec3(1.0f);
    e.texture = 0;
    const EnvironmentMap map(e, textures);
    // Its share of luminance times solid angle.
    auto solidAngle = [&](int row) {
        return 2.0 * kPi / w * (std::cos(kPi * row / h) - std::cos(kPi * (row + 1) / h));
    };
    double total = 0;
    for (int y = 0; y < h; ++y) total += solidAngle(y) * (w - 1 + (y == 9 ? 1e6 : 1.0));
    const double share = 1e6 * solidAngle(9) / total;
    int hits = 0;
    const int n = 4096;
    for (int i = 0; i < n; ++i) {
        const glm::vec2 u(Sobol::scrambled(std::uint32_t(i), 0, 0),
                          Sobol::scrambled(std::uint32_t(i), 1, 0));
        hits += map.sample(u).radiance.x > 1.0f;
    }
    EXPECT_NEAR(double(hits) / n, share, 0.01);
    EXPECT_GT(share, 0.99);
}

// A diffuse sphere in a constant sky sees only the sky: its radiance is albedo x L.
Scene sphereInTheSky(float radius, float sky) {
    Scene scene;
    scene.materials.push_back(testing::diffuse(glm::vec3(0.5f)));
    scene.meshes.push_back(testing::makeIcosphere(4, radius, glm::vec3(0), 0));
    scene.environment.radiance = glm::vec3(sky);
    scene.camera = {glm::vec3(0, 0, 5.0f * radius), glm::vec3(0), glm::vec3(0, 1, 0), 30};
    scene.image = {24, 18, 0};
    scene.render.causticPhotons = 0;
    return scene;
}

struct FurnaceCase {
    IntegratorKind integrator;
    float radius, sky;
};

class SkyFurnace : public ::testing::TestWithParam<FurnaceCase> {};

TEST_P(SkyFurnace, ADiffuseSphereConvergesToAlbedoTimesTheSky) {
    const FurnaceCase c = GetParam();
    Scene scene = sphereInTheSky(c.radius, c.sky);
    scene.render.integrator = c.integrator;
    scene.render.pathSamples = 16;
    InProcessRenderer renderer(scene);
    const Image image = renderer.render(c.integrator == IntegratorKind::Path ? 4 : 16);
    // The middle of the image is on the sphere, the corners are sky.
    double sum = 0;
    int count = 0;
    for (int y = 6; y < 12; ++y)
        for (int x = 9; x < 15; ++x) sum += image.at(x, y).x, ++count;
    EXPECT_NEAR(sum / count / (0.5 * c.sky), 1.0, 0.02);
    EXPECT_FLOAT_EQ(image.at(0, 0).x, c.sky);
    for (const auto& p : image.pixels) ASSERT_TRUE(isFinite(p));
}

INSTANTIATE_TEST_SUITE_P(Scales, SkyFurnace,
                         ::testing::Values(FurnaceCase{IntegratorKind::Igi, 1.0f, 1.0f},
                                           FurnaceCase{IntegratorKind::Igi, 1e-3f, 1e3f},
                                           FurnaceCase{IntegratorKind::Igi, 1e3f, 1e-3f},
                                           FurnaceCase{IntegratorKind::Path, 1.0f, 1.0f},
                                           FurnaceCase{IntegratorKind::Path, 1e3f, 1e3f}));

// A mirror ball seen from +Z reflects, at its centre, what lies behind the camera (+Z: u =
// 0.75 of the map, the middle of column 4 of 6); past the ball the camera sees the sky in front
// of it. Each column covers 60 degrees, so no pixel is near a border.
TEST(SkyOrientation, AMirrorBallReflectsTheTexelBehindTheCamera) {
    const int w = 6, h = 3;
    Texture t;
    t.path = "columns.exr";
    t.width = w;
    t.height = h;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) t.texels.push_back(glm::vec3(float(x + 1)));
    Scene scene;
    Material mirror = testing::diffuse(glm::vec3(0.0f));
    mirror.reflection = Reflection::Mirror;
    mirror.specular = glm::vec3(1.0f);
    scene.materials.push_back(mirror);
    scene.meshes.push_back(testing::makeIcosphere(5, 1.0f, glm::vec3(0), 0));
    scene.textures.push_back(t);
    scene.environment.radiance = glm::vec3(1.0f);
    scene.environment.texture = 0;
    scene.camera = {glm::vec3(0, 0, 4), glm::vec3(0), glm::vec3(0, 1, 0), 40};
    scene.image = {33, 33, 0};
    scene.render.causticPhotons = 0;
    InProcessRenderer renderer(scene);
    const Image image = renderer.render(1);
    EXPECT_FLOAT_EQ(image.at(16, 16).x, 5.0f);  // column 4: +Z
    // The left edge looks along -Z turned 20 degrees toward -X: u = 0.19, column 1.
    EXPECT_FLOAT_EQ(image.at(0, 16).x, 2.0f);
    // The sky turned by 60 degrees (right-handed about +Y): +Z sees what was 60 degrees from
    // it toward -X, u = 0.92, column 5.
    scene.environment.rotateDeg = 60.0f;
    InProcessRenderer turned(scene);
    EXPECT_FLOAT_EQ(turned.render(1).at(16, 16).x, 6.0f);
}

// A floor under a smooth sky and under a sky with one texel 1e6 times the rest: converged, IGI
// agrees with the path tracer, and every pixel is finite.
void expectIgiMatchesPathTracerUnder(const Texture& sky, double tolerance) {
    Scene scene;
    scene.materials.push_back(testing::diffuse(glm::vec3(0.6f)));
    Material glossy = testing::diffuse(glm::vec3(0.3f));
    glossy.reflection = Reflection::Ggx;
    glossy.roughness = 0.3f;
    glossy.metallic = 0.0f;
    scene.materials.push_back(glossy);
    scene.meshes.push_back(testing::makeQuad({-2, 0, -2}, {0, 0, 4}, {4, 0, 0}, 0));
    scene.meshes.push_back(testing::makeBox({0, 0.4f, 0}, {0.4f, 0.4f, 0.4f}, 20.0f, 1));
    scene.textures.push_back(sky);
    scene.environment.radiance = glm::vec3(1.0f);
    scene.environment.texture = 0;
    scene.camera = {{0.5f, 1.6f, 2.4f}, {0, 0.3f, 0}, {0, 1, 0}, 45};
    scene.image = {32, 24, 0};
    scene.render.causticPhotons = 0;
    const testing::IgiAndPathImages r = testing::renderIgiAndPath(scene, 32, 256);
    EXPECT_EQ(r.nonFinite, 0u);
    const double ma = r.igiMean().y, mb = r.pathMean().y;
    std::printf("under %s: igi %.5g, path tracer %.5g\n", sky.path.c_str(), ma, mb);
    EXPECT_NEAR(ma / mb, 1.0, tolerance);
}

TEST(SkyLight, ConvergedIgiMatchesThePathTracerUnderASmoothSky) {
    expectIgiMatchesPathTracerUnder(smoothSky(64, 32), 0.02);
}

TEST(SkyLight, ASunTexelAMillionTimesTheRestIsFoundAndStaysFinite) {
    Texture t = oneBrightTexel(64, 32, 20, 6, 1e-3f, 1e3f);
    t.path = "one-texel.exr";
    expectIgiMatchesPathTracerUnder(t, 0.05);
}

}  // namespace
}  // namespace igi
