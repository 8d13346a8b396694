// The non-delta BRDF: its sampling density is the density of its sampler, it integrates to one,
// the lobe's weight is its BRDF times cosine over its density, and the MIS weights of two
// strategies sum to one.
#include "materials/SurfaceBrdf.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "math/Frame.h"
#include "math/Optics.h"
#include "math/Warp.h"
#include "shading/ConnectionBound.h"
#include "shading/Scattering.h"
#include "testing/SphereGrid.h"

namespace igi {
namespace {

using testing::integrateOverSphere;

SurfaceBrdf brdf(float kd, float ks, float exponent) {
    return SurfaceBrdf::make(glm::vec3(kd), glm::vec3(ks), exponent, glm::vec3(0, 0, 1));
}

class Lobes : public ::testing::TestWithParam<float> {};  // the Phong exponent

// The density that MIS uses integrates to one over the sphere, for the Phong lobe alone and for
// the mixture, whatever the direction of view (the Phong lobe about a grazing mirror direction
// reaches below the horizon, where sample() still puts directions: those count).
TEST_P(Lobes, DensityIntegratesToOne) {
    const float n = GetParam();
    for (const float viewCos : {1.0f, 0.5f, 0.05f}) {
        const glm::vec3 wo(std::sqrt(1 - viewCos * viewCos), 0.0f, viewCos);
        for (SurfaceBrdf b : {brdf(0.0f, 0.5f, n), brdf(0.6f, 0.3f, n)}) {
            b.mirror = reflect(wo, b.normal);
            const double total = integrateOverSphere([&](glm::vec3 w) { return double(b.pdf(w)); });
            EXPECT_NEAR(total, 1.0, 2e-3) << "n " << n << ", cos " << viewCos;
        }
    }
}

// The density is the sampler's: the mean of g / pdf over sampled directions is the integral of
// g, for a g that weighs the lobe's peak and its flanks differently.
TEST_P(Lobes, DensityMatchesTheSampler) {
    const float n = GetParam();
    SurfaceBrdf b = brdf(0.5f, 0.4f, n);
    const glm::vec3 wo = glm::normalize(glm::vec3(0.6f, 0.1f, 0.8f));
    const glm::vec3 mirror = reflect(wo, b.normal);
    b.mirror = mirror;
    auto g = [&](glm::vec3 w) {
        return double(std::max(0.0f, w.z)) * (1.0 + 3.0 * double(w.x) * double(w.x)) +
               double(b.lobe(glm::dot(w, mirror)));
    };
    const double exact = integrateOverSphere(g);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const int samples = 400000;
    double sum = 0;
    for (int i = 0; i < samples; ++i) {
        const glm::vec3 w = b.sample({u(rng), u(rng)}, u(rng));
        sum += g(w) / double(b.pdf(w));
    }
    EXPECT_NEAR(sum / samples / exact, 1.0, 0.01) << "n " << n;
}

// A glossy lobe's sampled weight is its BRDF times cosine over its own (Phong) density, and the
// BRDF conserves energy: its directional albedo stays below ks.
TEST_P(Lobes, GlossyWeightIsBrdfTimesCosineOverDensityAndConservesEnergy) {
    const float n = GetParam();
    SurfacePoint hit;
    Material m;
    m.diffuse = glm::vec3(0.0f);
    m.specular = glm::vec3(0.7f);
    m.phongExponent = n;
    m.reflection = Reflection::Glossy;
    hit.material = &m;
    hit.geometricNormal = hit.shadingNormal = glm::vec3(0, 0, 1);
    const glm::vec3 wo = glm::normalize(glm::vec3(0.3f, 0.0f, 1.0f));
    const igi::Lobes l = lobesAt(hit, wo);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < 1000; ++i) {
        glm::vec3 w, weight;
        if (!sampleLobe(l, Lobe::Glossy, {u(rng), u(rng)}, 0.5f, w, weight)) continue;
        const float cosAlpha = glm::dot(w, l.mirrorDirection);
        const float phongPdf = (n + 1.0f) / (2.0f * kPi) * std::pow(cosAlpha, n);
        const glm::vec3 expected = l.brdf.glossy(w) * (w.z / phongPdf);
        ASSERT_NEAR(weight.x, expected.x, 1e-4f * std::max(1.0f, expected.x));
    }
    const double albedo = integrateOverSphere(
        [&](glm::vec3 w) { return w.z > 0 ? double(l.brdf.glossy(w).x) * w.z : 0.0; });
    EXPECT_LE(albedo, 0.7 * 1.001);
    EXPECT_GT(albedo, 0.7 * 0.8);
}

INSTANTIATE_TEST_SUITE_P(Exponents, Lobes, ::testing::Values(1.0f, 10.0f, 40.0f, 200.0f));

// The sharpness is pi times the BRDF normalized to unit albedo: 1 on a Lambertian surface, and
// (n + 2) / 2 in the peak of a pure Phong lobe.
TEST(SurfaceBrdf, SharpnessOfLambertAndPhong) {
    // Seen straight on: the mirror direction is the normal, and cos(alpha) is w.z.
    auto seen = [](SurfaceBrdf b) {
        b.mirror = b.normal;
        return b;
    };
    auto at = [](float cosAlpha) {
        return glm::vec3(std::sqrt(1 - cosAlpha * cosAlpha), 0.0f, cosAlpha);
    };
    EXPECT_FLOAT_EQ(seen(brdf(0.7f, 0.0f, 0.0f)).sharpness(at(0.3f)), 1.0f);
    EXPECT_FLOAT_EQ(seen(brdf(0.0f, 0.5f, 40.0f)).maxSharpness(), 21.0f);
    EXPECT_FLOAT_EQ(seen(brdf(0.0f, 0.5f, 40.0f)).sharpness(at(1.0f)), 21.0f);
    EXPECT_FLOAT_EQ(seen(brdf(0.5f, 0.5f, 40.0f)).sharpness(at(0.0f)), 0.5f);
}

// The power heuristic's weights of two strategies sum to one, and a strategy that cannot
// produce the sample gets none of it.
TEST(MultipleImportanceSampling, WeightsSumToOne) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(1e-3f, 1e3f);
    for (int i = 0; i < 1000; ++i) {
        const float a = u(rng), b = u(rng);
        ASSERT_NEAR(powerHeuristic(a, b) + powerHeuristic(b, a), 1.0f, 1e-6f);
    }
    EXPECT_EQ(powerHeuristic(0.0f, 3.0f), 0.0f);
    EXPECT_EQ(powerHeuristic(3.0f, 0.0f), 1.0f);
}

// The bound keeps Lambertian connections beyond dmin whole and clamps them like G <= 1 / dmin^2
// inside; a glossy receiver's lobe beyond the sharpness budget is cut at any distance.
TEST(ConnectionBound, ClampAndBudget) {
    const float dmin2 = 0.04f, budget = 4.0f;
    EXPECT_EQ(keptFraction(1.0f, dmin2, budget, 1.0f, 1.0f), 1.0f);
    EXPECT_FLOAT_EQ(keptFraction(0.01f, dmin2, budget, 1.0f, 1.0f), 0.25f);   // d^2 / dmin^2
    EXPECT_FLOAT_EQ(keptFraction(100.0f, dmin2, budget, 8.0f, 1.0f), 0.5f);   // budget / s_x
    EXPECT_EQ(keptFraction(100.0f, dmin2, budget, 1.0f, 8.0f), 1.0f);         // a glossy VPL, far
    EXPECT_FLOAT_EQ(keptFraction(0.04f, dmin2, budget, 1.0f, 8.0f), 0.125f);  // ... and near
    // A side of a glossy surface away from its lobe (sharpness below 1, its diffuse share) is
    // clamped as a Lambertian one, never closer: at either end, the clamp of sharpness 1.
    EXPECT_FLOAT_EQ(keptFraction(0.01f, dmin2, budget, 0.5f, 1.0f), 0.25f);
    EXPECT_FLOAT_EQ(keptFraction(0.01f, dmin2, budget, 1.0f, 0.5f), 0.25f);
    EXPECT_FLOAT_EQ(keptFraction(0.01f, dmin2, budget, 0.5f, 0.5f), 0.25f);
    EXPECT_TRUE(ConnectionBound::of(0.01f, dmin2, budget, 0.5f).cuts(0.5f));
    // The residual of a connection reached by a compensation ray is what the bound removed.
    const ConnectionBound bound = ConnectionBound::of(0.02f, dmin2, budget, 2.0f);
    EXPECT_FLOAT_EQ(bound.kept(1.0f), keptFraction(0.02f, dmin2, budget, 2.0f, 1.0f));
    EXPECT_TRUE(bound.cuts(1.0f));
    EXPECT_FALSE(ConnectionBound::of(1.0f, dmin2, budget, 1.0f).cuts(1.0f));
}

}  // namespace
}  // namespace igi
