#include "integrators/IgiIntegrator.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "math/Color.h"
#include "math/Warp.h"
#include "testing/TestScenes.h"

namespace igi {
namespace {

using testing::InProcessRenderer;

// Inside a closed diffuse sphere of radius R and albedo rho with a point light of intensity I at
// its centre, every point sees irradiance I / R^2 directly and the converged radiance is
// rho I / (pi R^2 (1 - rho)) (direct plus all indirect bounces).
Scene closedSphere(float radius, float albedo) {
    Scene scene;
    scene.materials.push_back(testing::diffuse(glm::vec3(albedo)));
    scene.meshes.push_back(testing::makeIcosphere(5, radius, glm::vec3(0), 0));
    scene.punctualLights.push_back(
        pointLight("centre", glm::vec3(0), glm::vec3(radius * radius)));  // I / R^2 = 1
    scene.camera = {glm::vec3(0), glm::vec3(1, 0.2f, 0.1f), glm::vec3(0, 1, 0), 70};
    scene.image = {24, 18, 0};
    scene.render.maxLightPathLength = 64;  // the analytic answer sums every bounce
    scene.render.causticPhotons = 0;
    return scene;
}

class ClosedSphere : public ::testing::TestWithParam<float> {};

TEST_P(ClosedSphere, AccumulatedIgiIsWithinTwoPercentOfTheAnalyticRadiance) {
    const float radius = GetParam(), albedo = 0.5f;
    InProcessRenderer renderer(closedSphere(radius, albedo));
    const Image image = renderer.render(24);
    const double expected = albedo / (kPi * (1.0 - albedo));  // I / R^2 = 1
    const glm::dvec3 mean = testing::meanOf(image);
    EXPECT_NEAR(mean.x / expected, 1.0, 0.02) << "R = " << radius;
    for (const auto& p : image.pixels) {
        ASSERT_TRUE(isFinite(p));
        EXPECT_NEAR(p.x / expected, 1.0, 0.1) << "R = " << radius;  // no pixel far off either
    }
}

INSTANTIATE_TEST_SUITE_P(Scales, ClosedSphere, ::testing::Values(1e-3f, 1.0f, 1e3f));

TEST(ClosedSphere, PathTracerConvergesToTheSameAnswer) {
    Scene scene = closedSphere(1.0f, 0.5f);
    scene.render.integrator = IntegratorKind::Path;
    scene.render.pathSamples = 64;
    scene.render.maxPathLength = 64;
    InProcessRenderer renderer(scene);
    const double expected = 0.5 / (kPi * 0.5);
    EXPECT_NEAR(testing::meanOf(renderer.render(2)).x / expected, 1.0, 0.02);
}

TEST(ClosedSphere, DirectLightAloneIsExact) {
    // Light paths of length 1 (the light only): no VPL, only the direct samples.
    Scene scene = closedSphere(1.0f, 0.5f);
    scene.render.roulette = false;
    scene.render.maxLightPathLength = 1;
    InProcessRenderer renderer(scene);
    const double expected = 0.5 / kPi;
    const Image image = renderer.render(1);
    for (const auto& p : image.pixels) ASSERT_NEAR(p.x / expected, 1.0, 0.01);
}

// A glossy furnace: the closed sphere with Kd + Ks < 1 and a Phong lobe. No closed form, but
// IGI's converged energy (light samples and glossy VPLs through the whole BRDF at both ends,
// bounded and compensated) must match the path tracer's at every scale.
class GlossySphere : public ::testing::TestWithParam<float> {};

TEST_P(GlossySphere, ConvergedIgiMatchesThePathTracerWithinTwoPercent) {
    const float radius = GetParam();
    Scene scene = closedSphere(radius, 0.4f);
    Material& m = scene.materials[0];
    m.specular = glm::vec3(0.35f);
    m.phongExponent = 20.0f;
    m.reflection = Reflection::Glossy;
    const testing::IgiAndPathImages r = testing::renderIgiAndPath(scene, 48, 128, 4, 64);
    EXPECT_EQ(r.nonFinite, 0u);
    const double ratio = r.igiMean().x / r.pathMean().x;
    std::printf("glossy sphere, R = %g: IGI / path tracer %.4f\n", radius, ratio);
    EXPECT_NEAR(ratio, 1.0, 0.02) << "R = " << radius;
}

INSTANTIATE_TEST_SUITE_P(Scales, GlossySphere, ::testing::Values(1e-3f, 1.0f, 1e3f));

bool sameBits(glm::vec3 a, glm::vec3 b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

// Pixels shaded together (eye rays in packets, shadow rays traced by target across the pixels)
// must come out exactly as each shaded alone, in any company and order: else an image would
// depend on how the tiles were cut into chunks, and so on which client rendered what.
TEST(IgiIntegrator, APixelShadedWithOthersIsThePixelShadedAlone) {
    for (const bool accumulated : {false, true}) {
        Scene scene = testing::cornellBox(1.0f, true);
        scene.materials[0].specular = glm::vec3(0.3f);  // a glossy floor and back wall: MIS and
        scene.materials[0].phongExponent = 30.0f;       // continuations, besides the glass
        scene.materials[0].reflection = Reflection::Glossy;
        // A half-mirror red wall: one delta lobe, so a pixel shaded alone traces its mirror ray
        // alone, and together in a packet with its neighbours'.
        scene.materials[1].specular = glm::vec3(0.5f);
        scene.materials[1].reflection = Reflection::Mirror;
        scene.image = {48, 36, 0};
        InProcessRenderer renderer(scene);
        TileRenderer& tiles = renderer.renderer();
        bool built = false;
        const auto set = tiles.cache().get(3, accumulated ? 5 : 0, 4, built);
        const IgiIntegrator igi(renderer.traceable(), tiles.lights(), scene.render, tiles.camera());
        std::vector<IgiIntegrator::Pixel> pixels;
        for (int y = 0; y < scene.image.height; ++y)
            for (int x = 0; x < scene.image.width; ++x)
                pixels.push_back({x, y, std::uint32_t(y * scene.image.width + x)});
        std::reverse(pixels.begin() + 100, pixels.begin() + 300);  // any order
        std::vector<PixelResult> together(pixels.size());
        RayCounters a, b;
        for (std::size_t begin = 0; begin < pixels.size(); begin += 150)
            igi.shade(&pixels[begin], int(std::min<std::size_t>(150, pixels.size() - begin)), 3,
                      *set, &together[begin], a);
        int lit = 0;
        for (std::size_t i = 0; i < pixels.size(); ++i) {
            const PixelResult alone =
                igi.shade(pixels[i].x, pixels[i].y, pixels[i].index, 3, *set, b);
            const PixelResult& t = together[i];
            ASSERT_TRUE(
                sameBits(t.irradiance, alone.irradiance) && sameBits(t.glossy, alone.glossy) &&
                sameBits(t.unfiltered, alone.unfiltered) &&
                sameBits(t.reflectance, alone.reflectance) && sameBits(t.normal, alone.normal) &&
                t.depth == alone.depth && t.firstHit == alone.firstHit)
                << "pixel " << pixels[i].x << ", " << pixels[i].y;
            lit += luminance(t.irradiance) > 0 && luminance(t.glossy) > 0;
        }
        EXPECT_GT(lit, int(pixels.size()) / 4) << "the glossy surfaces are seen and lit";
        EXPECT_EQ(a.rays, b.rays);
        EXPECT_EQ(a.shadowRays, b.shadowRays);
    }
}

// A Lambertian point tests its set's light samples and VPLs many at a time (LambertianLinks)
// where the set laid them out, one at a time where it did not (sets made elsewhere): both must
// give every pixel the same bits, for the area light's samples and the point light's alike.
TEST(IgiIntegrator, ConnectionsInLanesGiveTheBitsOfConnectionsOneAtATime) {
    Scene scene = testing::cornellBox(1.0f);
    ASSERT_FALSE(scene.punctualLights.empty());
    scene.image = {40, 30, 0};
    InProcessRenderer renderer(scene);
    TileRenderer& tiles = renderer.renderer();
    bool built = false;
    const auto set = tiles.cache().get(2, 0, 1, built);
    ASSERT_TRUE(set->directLanes.laidOut(set->direct.size()));
    ASSERT_TRUE(set->vplChoice.laidOut(set->indirect.size()));
    LightingSet alone = *set;
    alone.directLanes = VplChoice{};
    alone.vplChoice = VplChoice{};
    ASSERT_FALSE(alone.directLanes.laidOut(alone.direct.size()));
    const IgiIntegrator igi(renderer.traceable(), tiles.lights(), scene.render, tiles.camera());
    RayCounters a, b;
    int lit = 0;
    for (int y = 0; y < scene.image.height; ++y)
        for (int x = 0; x < scene.image.width; ++x) {
            const auto index = std::uint32_t(y * scene.image.width + x);
            const PixelResult lanes = igi.shade(x, y, index, 2, *set, a);
            const PixelResult scalar = igi.shade(x, y, index, 2, alone, b);
            ASSERT_TRUE(sameBits(lanes.irradiance, scalar.irradiance) &&
                        sameBits(lanes.glossy, scalar.glossy) &&
                        sameBits(lanes.unfiltered, scalar.unfiltered))
                << "pixel " << x << ", " << y;
            lit += luminance(lanes.irradiance) > 0;
        }
    EXPECT_GT(lit, scene.image.width * scene.image.height / 2);
    EXPECT_EQ(a.shadowRays, b.shadowRays);
}

// IGI's first frame after a change shades no second point: a glossy point's continuation ray
// finds the lights its lobe sees, but does not shade where it lands to restore the bound's cut
// (LightingSet::compensationRays). The same set allowed those rays traces more shadow rays.
TEST(IgiIntegrator, TheFirstFramesGlossyPointsShadeNoSecondPoint) {
    Scene scene = testing::cornellBox(1.0f);
    scene.materials[0].specular = glm::vec3(0.3f);  // a glossy floor and back wall
    scene.materials[0].phongExponent = 30.0f;
    scene.materials[0].reflection = Reflection::Glossy;
    scene.image = {40, 30, 0};
    ASSERT_EQ(scene.render.clampCompensation, ClampCompensation::KolligKeller);
    InProcessRenderer renderer(scene);
    TileRenderer& tiles = renderer.renderer();
    bool built = false;
    const auto set = tiles.cache().get(2, 0, 1, built);
    ASSERT_FALSE(set->compensationRays);
    LightingSet compensated = *set;
    compensated.compensationRays = true;
    const IgiIntegrator igi(renderer.traceable(), tiles.lights(), scene.render, tiles.camera());
    RayCounters first, withRays;
    for (int y = 0; y < scene.image.height; ++y)
        for (int x = 0; x < scene.image.width; ++x) {
            const auto index = std::uint32_t(y * scene.image.width + x);
            igi.shade(x, y, index, 2, *set, first);
            igi.shade(x, y, index, 2, compensated, withRays);
        }
    EXPECT_GT(first.shadowRays, 0u);
    EXPECT_GT(withRays.shadowRays, first.shadowRays + first.shadowRays / 10)
        << "the glossy points shade where their rays land when the set allows it";
}

}  // namespace
}  // namespace igi
