// Rough glass's BSDF (client/materials/RoughDielectric.h: GGX reflection and refraction,
// Walter et al. 2007): its density integrates to the share of samples its sampler keeps and is
// its sampler's (a chi-square test over the sphere), its sampled weight is f |cos| / pdf, its
// single-scatter albedo is the integral of f |cos| and never above one, reflection is
// reciprocal and refraction obeys the generalized reciprocity of Walter et al. (eq. 22);
// lobesAt maps glass with a GGX roughness to it.
#include "materials/RoughDielectric.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "math/Color.h"
#include "shading/Scattering.h"
#include "testing/SphereGrid.h"

namespace igi {
namespace {

using testing::integrateOverSphere;
using testing::viewAt;

using roughdielectric::Transport;

struct Case {
    float alpha, eta;
};

std::ostream& operator<<(std::ostream& os, const Case& c) {
    return os << "alpha " << c.alpha << ", eta " << c.eta;
}

class RoughDielectricCase : public ::testing::TestWithParam<Case> {};

// The density's integral over the sphere is one minus what the sampler loses: reflections
// below the macro surface and refractions above it (masking). Total internal reflection loses
// nothing: where a microfacet reflects totally, the sampler reflects (F = 1) and the density
// has it. Both are measured, and must agree.
TEST_P(RoughDielectricCase, DensityIntegratesToTheSamplersShareOnTheRightSides) {
    const Case c = GetParam();
    if (c.alpha < 0.02f) GTEST_SKIP() << "a grid cannot integrate so sharp a lobe";
    for (const float viewCos : {1.0f, 0.7f, 0.2f}) {
        const glm::vec3 wo = viewAt(viewCos);
        const double total = integrateOverSphere(
            [&](glm::vec3 w) { return double(roughdielectric::pdfLocal(c.alpha, c.eta, wo, w)); },
            c.alpha < 0.1f ? 3072 : 1024);
        std::mt19937 rng(3);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        int kept = 0, reflected = 0;
        const int samples = 200000;
        for (int i = 0; i < samples; ++i) {
            roughdielectric::Sample s;
            const glm::vec2 uv(u(rng), u(rng));
            if (roughdielectric::sampleLocal(c.alpha, c.eta, wo, uv, u(rng), s)) {
                ++kept;
                reflected += s.refracted ? 0 : 1;
            }
        }
        std::printf(
            "%s alpha %.3f eta %.3f cos %.1f: density integral %.5f, kept %.5f, "
            "reflected %.4f\n",
            "RoughDielectric", double(c.alpha), double(c.eta), double(viewCos), total,
            double(kept) / samples, double(reflected) / samples);
        EXPECT_LE(total, 1.0 + 3e-3) << c << ", cos " << viewCos;
        EXPECT_NEAR(total, double(kept) / samples, 6e-3) << c << ", cos " << viewCos;
    }
}

// Chi-square of the sampler's directions against the density, over 20 x 40 cells of equal
// solid angle (uniform in z and phi), cells expecting fewer than 10 samples pooled.
TEST_P(RoughDielectricCase, DensityMatchesTheSamplerChiSquare) {
    const Case c = GetParam();
    if (c.alpha < 0.15f) GTEST_SKIP() << "the cells cannot resolve so sharp a lobe";
    const int nz = 20, nphi = 40, sub = 24;
    const glm::vec3 wo = glm::normalize(glm::vec3(0.6f, 0.1f, 0.5f));
    std::vector<double> expected(std::size_t(nz * nphi)), observed(expected.size(), 0.0);
    const int samples = 1000000;
    for (int i = 0; i < nz; ++i)
        for (int j = 0; j < nphi; ++j) {
            double sum = 0;
            for (int a = 0; a < sub; ++a)
                for (int b = 0; b < sub; ++b) {
                    const double z = -1.0 + (i + (a + 0.5) / sub) * 2.0 / nz;
                    const double phi = (j + (b + 0.5) / sub) * 2.0 * M_PI / nphi;
                    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
                    sum += roughdielectric::pdfLocal(
                        c.alpha, c.eta, wo,
                        glm::vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z)));
                }
            expected[std::size_t(i * nphi + j)] =
                sum / (sub * sub) * (4.0 * M_PI / (nz * nphi)) * samples;
        }
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int k = 0; k < samples; ++k) {
        roughdielectric::Sample s;
        const glm::vec2 uv(u(rng), u(rng));
        if (!roughdielectric::sampleLocal(c.alpha, c.eta, wo, uv, u(rng), s)) continue;
        const int i = std::clamp(int((s.wi.z + 1.0f) * 0.5f * nz), 0, nz - 1);
        float phi = std::atan2(s.wi.y, s.wi.x);
        if (phi < 0) phi += 2.0f * float(M_PI);
        const int j = std::clamp(int(phi / (2.0f * float(M_PI)) * nphi), 0, nphi - 1);
        observed[std::size_t(i * nphi + j)] += 1.0;
    }
    double chi2 = 0, pooledE = 0, pooledO = 0;
    int cells = 0;
    for (std::size_t k = 0; k < expected.size(); ++k) {
        if (expected[k] < 10.0) {
            pooledE += expected[k];
            pooledO += observed[k];
            continue;
        }
        const double d = observed[k] - expected[k];
        chi2 += d * d / expected[k];
        ++cells;
    }
    if (pooledE >= 10.0) {
        chi2 += (pooledO - pooledE) * (pooledO - pooledE) / pooledE;
        ++cells;
    }
    const double dof = cells - 1;
    std::printf("RoughDielectric alpha %.3f eta %.3f: chi-square %.1f over %d cells\n",
                double(c.alpha), double(c.eta), chi2, cells);
    ASSERT_GT(cells, 20);
    // Five standard deviations above the mean of a chi-square of dof degrees of freedom.
    EXPECT_LT(chi2, dof + 5.0 * std::sqrt(2.0 * dof)) << c;
}

// The sampler's weight is f |cos| / pdf for the direction it returns (never above one), and
// its mean over the sampler, the single-scatter albedo, is the integral of f |cos| over the
// sphere and at most one.
TEST_P(RoughDielectricCase, AlbedoIsTheIntegralOfFCosAndAtMostOne) {
    const Case c = GetParam();
    for (const float viewCos : {1.0f, 0.5f, 0.1f}) {
        const glm::vec3 wo = viewAt(viewCos);
        std::mt19937 rng(7);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        double sum = 0;
        const int samples = 200000;
        for (int i = 0; i < samples; ++i) {
            roughdielectric::Sample s;
            const glm::vec2 uv(u(rng), u(rng));
            if (!roughdielectric::sampleLocal(c.alpha, c.eta, wo, uv, u(rng), s)) continue;
            const float f = roughdielectric::evaluateLocal(c.alpha, c.eta, wo, s.wi);
            const float p = roughdielectric::pdfLocal(c.alpha, c.eta, wo, s.wi);
            ASSERT_GT(p, 0.0f);
            if (i < 2000) {
                const float expected = f * std::abs(s.wi.z) / p;
                EXPECT_NEAR(s.weight, expected, 2e-3f * std::max(1.0f, expected)) << c;
            }
            EXPECT_LE(s.weight, 1.0f + 1e-4f);
            sum += s.weight;
        }
        const double sampled = sum / samples;
        EXPECT_LE(sampled, 1.0 + 2e-3) << c << ", cos " << viewCos;
        if (c.alpha >= 0.15f) {
            const double exact = integrateOverSphere([&](glm::vec3 w) {
                return double(roughdielectric::evaluateLocal(c.alpha, c.eta, wo, w)) *
                       std::abs(double(w.z));
            });
            EXPECT_NEAR(sampled, exact, 0.01 * exact) << c << ", cos " << viewCos;
        }
        std::printf("RoughDielectric alpha %.3f eta %.3f cos %.1f: albedo %.4f\n", double(c.alpha),
                    double(c.eta), double(viewCos), sampled);
        // Seen head-on, a smooth interface scatters nearly all of the light.
        if (c.alpha <= 0.05f && viewCos == 1.0f) {
            EXPECT_NEAR(sampled, 1.0, 0.01) << c;
        }
    }
}

// Reflection is reciprocal; refraction obeys f_t(wi, wo) / eta_o^2 = f_t(wo, wi) / eta_i^2 for
// the radiance BTDF (eta_o, eta_i the indices on wo's and wi's sides); the importance form the
// renderer uses is the radiance BTDF with its directions exchanged (its adjoint).
TEST_P(RoughDielectricCase, ReflectionIsReciprocalAndRefractionGeneralizedReciprocal) {
    const Case c = GetParam();
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    auto flip = [](glm::vec3 w) { return glm::vec3(w.x, w.y, -w.z); };
    int refractions = 0;
    for (int i = 0; i < 2000; ++i) {
        const glm::vec3 wo = glm::normalize(glm::vec3(u(rng), u(rng), std::abs(u(rng)) + 0.01f));
        const glm::vec3 up = glm::normalize(glm::vec3(u(rng), u(rng), std::abs(u(rng)) + 0.01f));
        // Reflection: both above.
        const float fab =
            roughdielectric::evaluateLocal(c.alpha, c.eta, wo, up, Transport::Radiance);
        const float fba =
            roughdielectric::evaluateLocal(c.alpha, c.eta, up, wo, Transport::Radiance);
        // Relative 1e-3: float near the peak of the sharpest lobes.
        EXPECT_NEAR(fab, fba, 1e-3f * std::max(1.0f, fab)) << c;
        // Refraction: wi below. Seen from wi's side the normal is -z and eta is inverted.
        const glm::vec3 wi = flip(up);
        const float ft =
            roughdielectric::evaluateLocal(c.alpha, c.eta, wo, wi, Transport::Radiance);
        const float back = roughdielectric::evaluateLocal(c.alpha, 1.0f / c.eta, flip(wi), flip(wo),
                                                          Transport::Radiance);
        // eta_o = 1 (above), eta_i = eta (below).
        EXPECT_NEAR(ft / 1.0f, back / (c.eta * c.eta), 1e-3f * std::max(1.0f, ft)) << c;
        const float importance =
            roughdielectric::evaluateLocal(c.alpha, c.eta, wo, wi, Transport::Importance);
        EXPECT_NEAR(importance, back, 1e-3f * std::max(1.0f, back)) << c;
        EXPECT_TRUE(std::isfinite(ft) && ft >= 0 && std::isfinite(fab) && fab >= 0);
        refractions += ft > 0 ? 1 : 0;
    }
    EXPECT_GT(refractions, 200) << c;  // the test saw refraction, not only zeros
}

INSTANTIATE_TEST_SUITE_P(RoughnessAndSide, RoughDielectricCase,
                         ::testing::Values(Case{1.0f, 1.5f}, Case{1.0f, 1.0f / 1.5f},
                                           Case{0.5f, 1.5f}, Case{0.5f, 1.0f / 1.5f},
                                           Case{0.2f, 1.5f}, Case{0.2f, 1.0f / 1.5f},
                                           Case{0.06f, 1.5f}, Case{0.04f, 1.0f / 1.33f},
                                           Case{0.01f, 1.5f}));

// glass with a GGX roughness is rough glass in lobesAt: one lobe, the interface's BSDF, whose
// sampled weight is its value times |cos| over its density (the tint on refraction only);
// under the mirror threshold it is the smooth glass of before.
TEST(RoughGlassLobes, LobesAtMapsGlassWithRoughnessToTheBsdf) {
    Material m;
    m.glass = true;
    m.ior = 1.5f;
    m.transmittance = {0.9f, 0.5f, 0.2f};
    m.reflection = Reflection::Ggx;
    SurfacePoint hit;
    hit.material = &m;
    hit.geometricNormal = hit.shadingNormal = {0, 0, 1};
    hit.roughness = 0.5f;
    for (const glm::vec3 wo : {glm::normalize(glm::vec3(0.3f, 0.2f, 0.9f)),
                               glm::normalize(glm::vec3(0.3f, 0.2f, -0.9f))}) {
        const Lobes l = lobesAt(hit, wo);
        ASSERT_TRUE(l.roughGlass());
        EXPECT_FLOAT_EQ(l.roughAlpha, 0.25f);
        EXPECT_FLOAT_EQ(l.eta, wo.z > 0 ? 1.5f : 1.0f / 1.5f);
        EXPECT_FALSE(l.hasNonDelta());
        EXPECT_TRUE(isBlack(l.reflection));
        std::mt19937 rng(2);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        int refracted = 0, reflected = 0;
        for (int i = 0; i < 400; ++i) {
            glm::vec3 direction, weight;
            const glm::vec2 uv(u(rng), u(rng));
            if (!sampleLobe(l, Lobe::Transmission, uv, u(rng), direction, weight)) continue;
            const glm::vec3 expected =
                roughGlassValue(l, direction) *
                (std::abs(glm::dot(direction, l.normal)) / roughGlassPdf(l, direction));
            for (int k = 0; k < 3; ++k)
                EXPECT_NEAR(weight[k], expected[k], 2e-3f * std::max(1.0f, expected[k]));
            (glm::dot(direction, l.normal) < 0 ? refracted : reflected) += 1;
        }
        EXPECT_GT(refracted, 50);
        EXPECT_GT(reflected, 5);
    }
    hit.roughness = 0.03f;  // alpha 9e-4: smooth glass
    const Lobes smooth = lobesAt(hit, glm::vec3(0, 0, 1));
    EXPECT_FALSE(smooth.roughGlass());
    EXPECT_NEAR(smooth.reflection.x, 0.04f, 1e-4f);
    EXPECT_NEAR(smooth.transmission.x, 0.96f * 0.9f, 1e-4f);
}

}  // namespace
}  // namespace igi
