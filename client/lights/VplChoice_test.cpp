#include "lights/VplChoice.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "math/Color.h"
#include "scene/SceneLoader.h"
#include "testing/TestScenes.h"
#include "testing/TestVpls.h"
#include "util/TestPaths.h"

namespace igi {
namespace {

// VPLs scattered over a room, a few of them bright.
std::vector<Vpl> scatteredVpls(int count, std::mt19937& random) {
    return testing::roomVpls(count, random, {.fewBright = true});
}

// What VPL i gives the point (any function that is zero wherever the choice gives zero
// importance): the clamped Lambertian connection itself.
float contribution(const Vpl& v, glm::vec3 x, glm::vec3 n, float dmin2) {
    const glm::vec3 t = v.position - x;
    const float d2 = glm::dot(t, t), d = std::sqrt(d2);
    const float cx = glm::dot(n, t) / d, cy = -glm::dot(v.normal, t) / d;
    if (cx <= 0 || cy <= 0) return 0;
    return v.power.y * cx * cy / std::max(d2, dmin2);
}

// Averaged over the offsets of a whole frame's sets, the chosen VPLs' weighted contributions
// are the sum over all VPLs: the choice steers the estimate without biasing it.
TEST(VplChoice, ChosenVplsEstimateTheSumOverThePool) {
    std::mt19937 random(3);
    const auto vpls = scatteredVpls(144, random);
    const glm::vec3 x(0.5f, 0.0f, 0.2f), n(0, 1, 0);
    const float dmin2 = 0.2f * 0.2f;
    double exact = 0;
    for (const Vpl& v : vpls) exact += contribution(v, x, n, dmin2);
    ASSERT_GT(exact, 0);
    for (std::uint32_t perPoint : {1u, 4u, 18u, 60u}) {
        const int offsets = 4096;
        double sum = 0;
        std::vector<VplChoice::Pick> picks(perPoint);
        VplChoice choice;
        for (int k = 0; k < offsets; ++k) {
            choice.prepare(vpls, perPoint, (float(k) + 0.5f) / float(offsets));
            const std::uint32_t chosen = choice.choose(x, n, n, dmin2, picks.data());
            ASSERT_LE(chosen, perPoint);
            for (std::uint32_t i = 0; i < chosen; ++i) {
                if (i > 0) {
                    ASSERT_LT(picks[i - 1].index, picks[i].index);
                }
                const float c = contribution(vpls[picks[i].index], x, n, dmin2);
                ASSERT_GT(c, 0) << "a VPL that cannot light the point was chosen";
                sum += picks[i].scale * c;
            }
        }
        EXPECT_NEAR(sum / offsets / exact, 1.0, 1e-3) << perPoint << " per point";
    }
}

// Whatever the weights (many orders of magnitude apart, many zero, pools of any size), a point
// gets at most perPoint picks in increasing order, each with a finite positive weight, and
// nothing is written past them.
TEST(VplChoice, PicksStayWithinTheirCountForAnyWeights) {
    std::mt19937 random(11);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int trial = 0; trial < 2000; ++trial) {
        auto vpls = scatteredVpls(1 + int(u(random) * 200), random);
        for (Vpl& v : vpls) v.power *= std::pow(10.0f, 12 * u(random) - 6);
        for (Vpl& v : vpls)
            if (u(random) < 0.3f) v.power = glm::vec3(0.0f);
        const std::uint32_t perPoint = 1 + std::uint32_t(u(random) * 40);
        VplChoice choice;
        choice.prepare(vpls, perPoint, u(random) * 0.999999f);
        const VplChoice::Pick sentinel{0xDEADBEEFu, -7.0f};
        std::vector<VplChoice::Pick> picks(perPoint + 1, sentinel);
        const glm::vec3 x(8 * u(random) - 4, 3 * u(random), 6 * u(random) - 3);
        const glm::vec3 n =
            glm::normalize(glm::vec3(u(random) - 0.5f, u(random), u(random) - 0.5f));
        const std::uint32_t chosen = choice.choose(x, n, n, 0.01f, picks.data());
        ASSERT_LE(chosen, perPoint) << "trial " << trial;
        EXPECT_EQ(picks[perPoint].index, sentinel.index) << "trial " << trial;
        for (std::uint32_t i = 0; i < chosen; ++i) {
            if (i > 0) {
                ASSERT_LT(picks[i - 1].index, picks[i].index) << "trial " << trial;
            }
            ASSERT_LT(picks[i].index, vpls.size());
            ASSERT_TRUE(std::isfinite(picks[i].scale) && picks[i].scale > 0) << "trial " << trial;
        }
    }
}

// The importance follows the contribution: a point next to one bright VPL spends most of its
// choices on it, and one shadow ray carries them all.
TEST(VplChoice, ANearBrightVplIsChosenOnceForManySamples) {
    std::mt19937 random(5);
    auto vpls = scatteredVpls(72, random);
    const glm::vec3 x(0.0f, 0.0f, 0.0f), n(0, 1, 0);
    vpls[40].position = {0.0f, 0.3f, 0.0f};
    vpls[40].normal = {0, -1, 0};
    vpls[40].power = glm::vec3(30.0f);
    VplChoice choice;
    choice.prepare(vpls, 18, 0.37f);
    std::vector<VplChoice::Pick> picks(18);
    const std::uint32_t chosen = choice.choose(x, n, n, 0.01f, picks.data());
    ASSERT_GT(chosen, 0u);
    int found = -1;
    for (std::uint32_t i = 0; i < chosen; ++i)
        if (picks[i].index == 40) found = int(i);
    ASSERT_GE(found, 0);
    EXPECT_LT(chosen, 10u) << "the near VPL takes most of the 18 samples in one ray";
}

// Nothing can light a point that every VPL faces away from, or that faces away from them.
TEST(VplChoice, APointNoVplCanLightChoosesNone) {
    std::mt19937 random(9);
    auto vpls = scatteredVpls(20, random);
    for (Vpl& v : vpls) v.position.y = 2.0f, v.normal = {0, 1, 0};  // all above, facing up
    VplChoice choice;
    choice.prepare(vpls, 8, 0.5f);
    std::vector<VplChoice::Pick> picks(8);
    EXPECT_EQ(choice.choose({0, 0, 0}, {0, 1, 0}, {0, 1, 0}, 0.01f, picks.data()), 0u);
}

// GGX lobes at either end: a glossy metal point among VPLs on glossy metal, most of whose
// lobes send their light elsewhere. What each VPL gives the point is its lobe toward the point
// (Vpl::towards) through the point's lobe; the choice ranks by both, so a few choices per point
// estimate the sum with a fraction of the spread that the Lambertian proxy leaves (which ranks
// a GGX VPL by the flux it received, whatever its lobe sends the point's way).
float ggxContribution(const Vpl& v, const SurfaceBrdf& b, glm::vec3 x, float dmin2) {
    const glm::vec3 t = v.position - x;
    const float d2 = glm::dot(t, t), d = std::sqrt(d2);
    const glm::vec3 w = t / d;
    const float cx = glm::dot(b.normal, w), cy = -glm::dot(v.normal, w);
    if (cx <= 0 || cy <= 0) return 0;
    const glm::vec3 f = b.diffuse() + b.glossy(w);
    return luminance(v.towards(w).intensity * f) * cx * cy / std::max(d2, dmin2);
}

struct Spread {
    double mean, relativeDeviation;
};
// The estimate's mean and relative standard deviation over a frame's worth of offsets, with
// the VPLs ranked as `ranked` says and contributing as `vpls` do.
Spread spreadOf(const std::vector<Vpl>& ranked, const std::vector<Vpl>& vpls, const SurfaceBrdf& b,
                glm::vec3 x, float dmin2, std::uint32_t perPoint, const SurfaceBrdf* receiver) {
    const int offsets = 4096;
    double sum = 0, sum2 = 0;
    std::vector<VplChoice::Pick> picks(perPoint);
    VplChoice choice;
    for (int k = 0; k < offsets; ++k) {
        choice.prepare(ranked, perPoint, (float(k) + 0.5f) / float(offsets));
        const std::uint32_t chosen =
            choice.choose(x, b.normal, b.normal, dmin2, picks.data(), receiver);
        double e = 0;
        for (std::uint32_t i = 0; i < chosen; ++i)
            e += picks[i].scale * ggxContribution(vpls[picks[i].index], b, x, dmin2);
        sum += e, sum2 += e * e;
    }
    const double mean = sum / offsets;
    return {mean, std::sqrt(std::max(0.0, sum2 / offsets - mean * mean)) / mean};
}

TEST(VplChoice, GgxLobesAtEitherEndRankTheVplsByWhatTheySendThePoint) {
    std::mt19937 random(11);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<Vpl> vpls = scatteredVpls(144, random);
    for (std::size_t i = 0; i < vpls.size(); ++i) {
        Vpl& v = vpls[i];
        if (i % 3 == 0) continue;  // a third stay Lambertian
        // Glossy metal (alpha 0.1, no diffuse lobe), lit from a random direction above it.
        const glm::vec3 in = glm::normalize(
            v.normal + glm::vec3(u(random) - 0.5f, u(random) - 0.5f, u(random) - 0.5f));
        if (glm::dot(in, v.normal) <= 0.05f) continue;
        v.ggx = true;
        v.exponent = 0.1f;
        v.f0 = glm::vec3(0.9f);
        v.glossyPower = v.power * 4.0f;  // the flux it received
        v.power = glm::vec3(0.0f);
        v.mirror = 2.0f * glm::dot(v.normal, in) * v.normal - in;
        v.diffuseShare = 0.0f;
        v.glossyShare = 1.0f;
    }
    const glm::vec3 x(0.5f, 0.0f, 0.2f), n(0, 1, 0);
    const glm::vec3 view = glm::normalize(glm::vec3(0.3f, 1.0f, 0.5f));
    const SurfaceBrdf b = SurfaceBrdf::makeGgx(glm::vec3(0.05f), glm::vec3(0.8f), 0.15f, n,
                                               2.0f * glm::dot(n, view) * n - view);
    const float dmin2 = 0.2f * 0.2f;
    double exact = 0;
    for (const Vpl& v : vpls) exact += ggxContribution(v, b, x, dmin2);
    ASSERT_GT(exact, 0);
    // The Lambertian proxy: the same VPLs without their lobe's rank (ggx cleared, so the
    // choice sees lum(power + glossyPower) as it did), and no receiver.
    std::vector<Vpl> proxy = vpls;
    for (Vpl& v : proxy) v.ggx = false;
    for (std::uint32_t perPoint : {4u, 18u}) {
        const Spread ranked = spreadOf(vpls, vpls, b, x, dmin2, perPoint, &b);
        const Spread lambertian = spreadOf(proxy, vpls, b, x, dmin2, perPoint, nullptr);
        std::printf(
            "%u per point: relative deviation %.3f ranked by the lobes, %.3f by the "
            "Lambertian proxy\n",
            perPoint, ranked.relativeDeviation, lambertian.relativeDeviation);
        // Unbiased either way; the lobes' rank spreads less than a third as much.
        EXPECT_NEAR(ranked.mean / exact, 1.0, 2e-3) << perPoint;
        EXPECT_NEAR(lambertian.mean / exact, 1.0, 2e-3) << perPoint;
        EXPECT_LT(3.0 * ranked.relativeDeviation, lambertian.relativeDeviation) << perPoint;
    }
}

// Rendered: the interior (96 small lights, every point choosing 18 of a pool of 144 VPLs per set)
// converges to the image of every point connecting to all its set's VPLs.
Scene withVpls(const char* file, VplSampling sampling, int width, int height) {
    SceneLoadOptions options;
    options.allowOutsidePaths = true;
    Scene scene = loadSceneFile(testing::sourceDir() / file, options);
    scene.image.width = width;
    scene.image.height = height;
    scene.render.vplSampling = sampling;
    return scene;
}

TEST(VplChoice, InteriorConvergesToTheImageOfEveryVpl) {
    const char* file = "scenes/interior/diffuse.json";
    testing::InProcessRenderer importance(withVpls(file, VplSampling::Importance, 64, 48)),
        all(withVpls(file, VplSampling::All, 64, 48));
    const glm::dvec3 ma = testing::meanOf(importance.render(96)),
                     mb = testing::meanOf(all.render(96));
    EXPECT_EQ(importance.nonFiniteValues(), 0u);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(ma[c] / mb[c], 1.0, 0.01) << c;
}

double relativeMse(const Image& a, const Image& reference) {
    double sum = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        const double r = luminance(reference.pixels[i]), d = luminance(a.pixels[i]) - r;
        sum += d * d / (r * r + 1e-2);
    }
    return sum / double(a.pixels.size());
}

// In the Sponza atrium lit by 120 lights under the arcades (scenes/sponza/arcades.json), most of
// a set's VPLs are far from any given point: one frame choosing by importance is much closer to
// the converged image than one frame connecting every point to its set's 18 VPLs.
TEST(VplChoice, OneFrameAmongManyLightsIsCloserToTheConvergedImage) {
    const char* file = "scenes/sponza/arcades.json";
    if (!std::filesystem::exists(testing::sourceDir() / "../shared/scenes/sponza-dabrovic"))
        GTEST_SKIP() << "../shared/scenes is not here";
    testing::InProcessRenderer importance(withVpls(file, VplSampling::Importance, 80, 60)),
        all(withVpls(file, VplSampling::All, 80, 60));
    const Image converged = importance.render(128, 1000);
    // One frame after the first (the converging estimator), each against the converged image.
    const double errorImportance = relativeMse(importance.render(1, 7, 1), converged);
    const double errorAll = relativeMse(all.render(1, 7, 1), converged);
    std::printf("one frame's relMSE: importance %.4f, all %.4f\n", errorImportance, errorAll);
    EXPECT_LT(1.5 * errorImportance, errorAll);
}

}  // namespace
}  // namespace igi
