// The lobe choice of light paths, photons and delta chains (chooseLobe, then sampleLobe) on
// glTF's GGX metallic-roughness: the estimate divides by the probability the choice used, so
// the mean of weight / probability over the choices and the samples is the surface's albedo
// seen from wo, whatever the weights steering the choice (Fresnel-weighted F(f0, n.wo) for the
// GGX lobe against the Lambertian kd). The albedo is integrated here by brute force over the
// hemisphere, independently of either sampler.

#include <cmath>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "math/Color.h"
#include "math/Frame.h"
#include "sampling/Sobol.h"
#include "shading/Scattering.h"

namespace igi {
namespace {

Lobes ggxLobes(glm::vec3 kd, glm::vec3 f0, float alpha, float cosView) {
    Lobes l;
    l.normal = l.faceNormal = glm::vec3(0, 0, 1);
    l.wo = glm::vec3(std::sqrt(1.0f - cosView * cosView), 0.0f, cosView);
    l.mirrorDirection = 2.0f * glm::dot(l.wo, l.normal) * l.normal - l.wo;
    l.brdf = SurfaceBrdf::makeGgx(kd, f0, alpha, l.normal, l.mirrorDirection);
    return l;
}

// The integral of (kd / pi + f_ggx(w, wo)) cos over the hemisphere, midpoint rule in
// (cos theta, phi), fine enough near a sharp peak for alpha >= 0.1.
glm::dvec3 albedoByQuadrature(const Lobes& l) {
    const int nTheta = 1024, nPhi = 1024;
    glm::dvec3 sum(0.0);
    for (int i = 0; i < nTheta; ++i) {
        const double c = (i + 0.5) / nTheta, s = std::sqrt(1.0 - c * c);
        for (int j = 0; j < nPhi; ++j) {
            const double phi = 2.0 * kPi * (j + 0.5) / nPhi;
            const glm::vec3 w(float(s * std::cos(phi)), float(s * std::sin(phi)), float(c));
            sum += glm::dvec3(l.brdf.diffuse() + l.brdf.glossy(w)) * c;
        }
    }
    return sum * (2.0 * kPi / (double(nTheta) * nPhi));
}

// The mean of weight / probability over chooseLobe and sampleLobe, on a 2^18-point Sobol' set.
glm::dvec3 albedoByChoice(const Lobes& l, double& glossyShare) {
    const std::uint32_t n = 1u << 18;
    glm::dvec3 sum(0.0);
    std::uint32_t glossy = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
        const float uLobe = Sobol::toFloat(Sobol::sample(i, 0));
        const glm::vec2 u(Sobol::toFloat(Sobol::sample(i, 1)), Sobol::toFloat(Sobol::sample(i, 2)));
        Lobe lobe;
        float probability = 0;
        if (!chooseLobe(l, uLobe, lobe, probability)) continue;
        if (lobe == Lobe::Glossy) ++glossy;
        glm::vec3 direction, weight;
        if (!sampleLobe(l, lobe, u, 0.5f, direction, weight)) continue;
        sum += glm::dvec3(weight / probability);
    }
    glossyShare = double(glossy) / n;
    return sum / double(n);
}

TEST(LobeChoice, WeightOverTheChosenProbabilityEstimatesTheGgxAlbedo) {
    struct Case {
        glm::vec3 kd, f0;
        float alpha, cosView;
    };
    // A rough dielectric (the diffuse lobe mostly chosen), a glossy one seen at a grazing
    // angle (Fresnel takes over), a coloured metal, and a half-metal.
    const Case cases[] = {{glm::vec3(0.7f, 0.5f, 0.3f), glm::vec3(0.04f), 0.8f, 0.9f},
                          {glm::vec3(0.6f), glm::vec3(0.04f), 0.15f, 0.12f},
                          {glm::vec3(0.0f), glm::vec3(0.95f, 0.64f, 0.54f), 0.3f, 0.5f},
                          {glm::vec3(0.3f), glm::vec3(0.5f), 0.5f, 0.3f}};
    for (const Case& c : cases) {
        const Lobes l = ggxLobes(c.kd, c.f0, c.alpha, c.cosView);
        double glossyShare = 0;
        const glm::dvec3 chosen = albedoByChoice(l, glossyShare);
        const glm::dvec3 exact = albedoByQuadrature(l);
        // The choice follows the Fresnel-weighted lobe weights: F(f0, n.wo) against kd.
        const float f = meanComponent(ggx::schlick(c.f0, c.cosView)), d = meanComponent(c.kd);
        EXPECT_NEAR(glossyShare, f / (f + d), 1e-3) << c.alpha << " " << c.cosView;
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(chosen[k] / exact[k], 1.0, 5e-3) << c.alpha << " " << c.cosView << " " << k;
    }
}

}  // namespace
}  // namespace igi
