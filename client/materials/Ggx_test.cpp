// The glTF metallic-roughness lobe (client/materials/Ggx.h) as SurfaceBrdf carries it: its density
// integrates to one and is its sampler's, its sampled weight is f cos / pdf, its single-scatter
// albedo never exceeds one and equals the integral of f cos, and it is reciprocal.
#include "materials/Ggx.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "materials/SurfaceBrdf.h"
#include "math/Optics.h"
#include "shading/Scattering.h"
#include "testing/SphereGrid.h"

namespace igi {
namespace {

using testing::integrateOverSphere;
using testing::viewAt;

SurfaceBrdf ggxBrdf(float kd, float f0, float alpha, glm::vec3 wo) {
    const glm::vec3 n(0, 0, 1);
    return SurfaceBrdf::makeGgx(glm::vec3(kd), glm::vec3(f0), alpha, n, reflect(wo, n));
}

// Monte Carlo over the VNDF sampler: the mean of g(w) / pdf(w), and the share of samples that
// fell below the surface (rejected by every caller).
template <typename G>
double sampledMean(float alpha, glm::vec3 wo, G&& g, int samples, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const glm::vec3 n(0, 0, 1);
    double sum = 0;
    for (int i = 0; i < samples; ++i) {
        const glm::vec3 w = ggx::sample(alpha, n, wo, {u(rng), u(rng)});
        if (w.z <= 0) continue;
        const float p = ggx::pdf(alpha, n, w, wo);
        EXPECT_GT(p, 0.0f);
        if (p > 0) sum += g(w) / double(p);
    }
    return sum / samples;
}

class GgxAlpha : public ::testing::TestWithParam<float> {};

// The density's integral over the upper hemisphere is one minus what the visible normals send
// below it: the sampler's own share of rejected directions, so the two must agree.
TEST_P(GgxAlpha, DensityIntegratesToTheSamplersShareAboveTheSurface) {
    const float alpha = GetParam();
    if (alpha < 0.005f) GTEST_SKIP() << "a grid cannot integrate so sharp a lobe";
    const glm::vec3 n(0, 0, 1);
    for (const float viewCos : {1.0f, 0.7f, 0.2f}) {
        const glm::vec3 wo = viewAt(viewCos);
        const int steps = alpha < 0.05f ? 4096 : 1024;
        const double total = integrateOverSphere(
            [&](glm::vec3 w) { return double(ggx::pdf(alpha, n, w, wo)); }, steps);
        std::mt19937 rng(3);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        int above = 0;
        const int samples = 200000;
        for (int i = 0; i < samples; ++i)
            above += ggx::sample(alpha, n, wo, {u(rng), u(rng)}).z > 0 ? 1 : 0;
        EXPECT_LE(total, 1.0 + 3e-3) << "alpha " << alpha << ", cos " << viewCos;
        EXPECT_NEAR(total, double(above) / samples, 6e-3)
            << "alpha " << alpha << ", cos " << viewCos;
        // Seen straight on, a smooth lobe keeps nearly all its directions above the surface; a
        // rough one sends many below (the single-scatter energy loss).
        if (viewCos == 1.0f && alpha <= 0.05f) {
            EXPECT_NEAR(total, 1.0, 3e-3) << "alpha " << alpha;
        }
    }
}

// The density is the sampler's: the mean of g / pdf over sampled directions is the integral of
// g over the upper hemisphere, for a g that weighs the peak and the flanks differently.
TEST_P(GgxAlpha, DensityMatchesTheSampler) {
    const float alpha = GetParam();
    if (alpha < 0.05f) GTEST_SKIP() << "a grid cannot integrate so sharp a lobe";
    const glm::vec3 n(0, 0, 1);
    const glm::vec3 wo = glm::normalize(glm::vec3(0.6f, 0.1f, 0.8f));
    auto g = [&](glm::vec3 w) {
        return w.z > 0 ? double(w.z) * (1.0 + 3.0 * double(w.x) * double(w.x)) +
                             double(ggx::pdf(alpha, n, w, wo))
                       : 0.0;
    };
    const double exact = integrateOverSphere(g);
    const double estimate = sampledMean(alpha, wo, g, 400000, 11);
    EXPECT_NEAR(estimate / exact, 1.0, 0.01) << "alpha " << alpha;
}

// The white furnace of one scattering: the albedo of a metal of f0 = 1 (the integral of f cos
// over the hemisphere) is at most one, and the sampler's weights F G2 / G1 estimate the same
// integral (they are f cos / pdf).
TEST_P(GgxAlpha, MetalAlbedoIsTheIntegralOfFCosAndAtMostOne) {
    const float alpha = GetParam();
    const glm::vec3 n(0, 0, 1);
    for (const float viewCos : {1.0f, 0.5f, 0.1f}) {
        const glm::vec3 wo = viewAt(viewCos);
        auto fcos = [&](glm::vec3 w) {
            return double(ggx::evaluate(alpha, glm::vec3(1.0f), n, w, wo).x) *
                   std::max(0.0, double(w.z));
        };
        const double sampled = sampledMean(alpha, wo, fcos, 200000, 5);
        EXPECT_LE(sampled, 1.0 + 1e-3) << "alpha " << alpha << ", cos " << viewCos;
        EXPECT_GT(sampled, 0.3) << "alpha " << alpha << ", cos " << viewCos;
        if (alpha >= 0.05f) {
            const double exact = integrateOverSphere(fcos);
            EXPECT_NEAR(sampled, exact, 0.01 * exact) << "alpha " << alpha << ", cos " << viewCos;
        }
        // A smooth metal reflects nearly everything at normal incidence.
        if (alpha <= 0.01f && viewCos == 1.0f) {
            EXPECT_NEAR(sampled, 1.0, 0.01);
        }
    }
}

TEST_P(GgxAlpha, IsReciprocalAndItsSharpnessSymmetric) {
    const float alpha = GetParam();
    const glm::vec3 n(0, 0, 1);
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int i = 0; i < 1000; ++i) {
        const glm::vec3 a = glm::normalize(glm::vec3(u(rng), u(rng), std::abs(u(rng)) + 0.01f));
        const glm::vec3 b = glm::normalize(glm::vec3(u(rng), u(rng), std::abs(u(rng)) + 0.01f));
        const glm::vec3 fab = ggx::evaluate(alpha, glm::vec3(0.9f, 0.5f, 0.04f), n, a, b);
        const glm::vec3 fba = ggx::evaluate(alpha, glm::vec3(0.9f, 0.5f, 0.04f), n, b, a);
        EXPECT_NEAR(fab.y, fba.y, 1e-5f * std::max(1.0f, fab.y));
        EXPECT_EQ(ggx::sharpness(alpha, n, a, b), ggx::sharpness(alpha, n, b, a));
        EXPECT_LE(ggx::sharpness(alpha, n, a, b), ggx::maxSharpness(alpha));
        EXPECT_TRUE(std::isfinite(fab.x) && fab.x >= 0);
    }
}

INSTANTIATE_TEST_SUITE_P(Roughness, GgxAlpha,
                         ::testing::Values(1.0f, 0.5f, 0.25f, 0.1f, 0.05f, 0.01f, 0.002f));

// The mixture SurfaceBrdf draws from (diffuse and GGX, by the Fresnel-weighted shares) has the
// density pdf() gives: g / pdf averages to the integral of g.
TEST(GgxBrdf, MixtureDensityMatchesItsSampler) {
    const glm::vec3 wo = glm::normalize(glm::vec3(0.5f, -0.2f, 0.7f));
    for (const float alpha : {0.3f, 0.08f}) {
        const SurfaceBrdf b = ggxBrdf(0.5f, 0.04f, alpha, wo);
        ASSERT_GT(b.glossySampling(), 0.0f);
        ASSERT_LT(b.glossySampling(), 1.0f);
        // The view is the mirror direction's image: what the BRDF was made for.
        EXPECT_NEAR(glm::length(b.view() - wo), 0.0f, 1e-6f);
        auto g = [&](glm::vec3 w) {
            return w.z > 0 ? double(w.z) * (1.0 + double(w.y) * double(w.y)) : 0.0;
        };
        const double exact = integrateOverSphere(g);
        std::mt19937 rng(17);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        double sum = 0;
        const int samples = 400000;
        for (int i = 0; i < samples; ++i) {
            const glm::vec3 w = b.sample({u(rng), u(rng)}, u(rng));
            if (w.z <= 0) continue;
            sum += g(w) / double(b.pdf(w));
        }
        // Directions the GGX lobe sends below the surface are lost to the estimate: few at
        // this view.
        EXPECT_NEAR(sum / samples / exact, 1.0, 0.015) << "alpha " << alpha;
    }
}

// sampleLobe's weight for the glossy lobe is f cos / pdf of the GGX lobe alone, for the
// direction it returns.
TEST(GgxBrdf, SampledGlossyWeightIsFCosOverItsDensity) {
    SurfacePoint hit;
    Material m;
    m.reflection = Reflection::Ggx;
    m.metallic = 1.0f;
    m.roughness = 0.4f;
    hit.material = &m;
    hit.geometricNormal = hit.shadingNormal = {0, 0, 1};
    hit.albedo = {0.9f, 0.6f, 0.3f};
    hit.roughness = m.roughness;
    hit.metallic = m.metallic;
    const glm::vec3 wo = glm::normalize(glm::vec3(0.3f, 0.2f, 0.9f));
    const Lobes l = lobesAt(hit, wo);
    ASSERT_EQ(l.brdf.model, GlossyModel::Ggx);
    EXPECT_EQ(l.brdf.kd, glm::vec3(0.0f));  // a metal has no diffuse lobe
    std::mt19937 rng(2);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    int taken = 0;
    for (int i = 0; i < 200; ++i) {
        glm::vec3 direction, weight;
        if (!sampleLobe(l, Lobe::Glossy, {u(rng), u(rng)}, 0.5f, direction, weight)) continue;
        ++taken;
        const glm::vec3 expected =
            l.brdf.glossy(direction) *
            (direction.z / ggx::pdf(l.brdf.exponent, l.normal, direction, wo));
        EXPECT_NEAR(weight.x, expected.x, 1e-4f * expected.x);
        EXPECT_LE(weight.x, 1.0f + 1e-4f);  // F G2 / G1 with F <= 1
    }
    EXPECT_GT(taken, 150);
}

// glTF's material: f0 of 0.04 for a dielectric, the base colour for a metal, mixed by
// metallic; the diffuse lobe is the base colour times (1 - metallic)(1 - 0.04); a roughness
// whose alpha is under ggx::kMinAlpha is a mirror of Fresnel reflectance.
TEST(GgxBrdf, MetallicRoughnessMapsToTheLobes) {
    Material m;
    m.reflection = Reflection::Ggx;
    SurfacePoint hit;
    hit.material = &m;
    hit.geometricNormal = hit.shadingNormal = {0, 0, 1};
    hit.albedo = {0.5f, 0.5f, 0.5f};
    hit.roughness = 0.5f;
    hit.metallic = 0.25f;
    const glm::vec3 wo(0, 0, 1);
    Lobes l = lobesAt(hit, wo);
    EXPECT_NEAR(l.brdf.ks.x, 0.75f * 0.04f + 0.25f * 0.5f, 1e-6f);
    EXPECT_NEAR(l.brdf.kd.x, 0.5f * 0.75f * 0.96f, 1e-6f);
    EXPECT_NEAR(l.brdf.exponent, 0.25f, 1e-6f);  // alpha
    EXPECT_TRUE(isBlack(l.reflection));
    hit.roughness = 0.01f;
    l = lobesAt(hit, wo);
    EXPECT_FALSE(l.brdf.hasGlossy());
    EXPECT_NEAR(l.reflection.x, 0.75f * 0.04f + 0.25f * 0.5f, 1e-6f);
    EXPECT_TRUE(l.hasDelta());
    // Roughness 0 and 1, and metallic at its ends: finite lobes.
    for (const float r : {0.0f, 1.0f})
        for (const float metal : {0.0f, 1.0f}) {
            hit.roughness = r;
            hit.metallic = metal;
            l = lobesAt(hit, glm::normalize(glm::vec3(1.0f, 0.0f, 1e-4f)));
            EXPECT_TRUE(isFinite(l.brdf.ks) && isFinite(l.brdf.kd) && isFinite(l.reflection));
            EXPECT_TRUE(std::isfinite(l.brdf.maxSharpness()));
        }
}

}  // namespace
}  // namespace igi

namespace igi {
namespace {

// Near the peak of the smoothest lobe the distribution keeps its digits: the form
// cos^2 (a^2 - 1) + 1 lost about 2 % there to cancellation (review of issue 34).
TEST(GgxPrecision, TheDistributionNearItsPeakMatchesDoublePrecision) {
    const float alpha = ggx::kMinAlpha;
    for (const float c : {1.0f - 0x1p-20f, 1.0f - 0x1p-22f, 1.0f - 0x1p-18f, 1.0f}) {
        const double a2 = double(alpha) * double(alpha), cd = double(c);
        const double d = (1.0 - cd * cd) + a2 * cd * cd;
        const double expected = a2 / (3.14159265358979323846 * d * d);
        EXPECT_NEAR(ggx::distribution(alpha, c) / expected, 1.0, 1e-4) << "cos " << c;
    }
    EXPECT_TRUE(std::isfinite(ggx::distribution(alpha, 1.0000001f)));  // a rounded cosine
}

}  // namespace
}  // namespace igi
