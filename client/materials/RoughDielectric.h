#pragma once

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "materials/Ggx.h"
#include "math/Frame.h"
#include "math/Optics.h"

namespace igi {

/// A rough dielectric interface: the GGX microfacet BSDF of Walter, Marschner, Li and Torrance
/// (2007, "Microfacet Models for Refraction through Rough Surfaces"), as pbrt-v4's
/// DielectricBxDF writes it: reflection and refraction through microfacets of the
/// Trowbridge-Reitz distribution of alpha, the height-correlated Smith G2 and the exact
/// (unpolarized) dielectric Fresnel F of each microfacet:
///   reflection  f = F(wo.m) D(m) G2 / (4 |n.wi| |n.wo|),  m = normalize(wi + wo)
///   refraction  f = (1 - F(wo.m)) D(m) G2 |wi.m| |wo.m| / (|n.wi| |n.wo| (wi.m + wo.m / eta')^2)
///                   [/ eta'^2 for radiance],  m = normalize(eta' wi + wo),
/// eta' the index on wi's side over the index on wo's side. Sampled as pbrt-v4 does: a
/// microfacet normal from the distribution of normals visible from wo (Heitz 2018, ggx.h),
/// then reflection with probability F(wo.m) (1 under total internal reflection) and refraction
/// otherwise; the sample's weight f |cos| / pdf is G2 / G1(wo) either way (for importance, or
/// for radiance before its 1 / eta'^2).
///
/// Directions are unit and point away from the surface; `normal` is on wo's side (wo is above
/// it) and `eta` is the index of refraction below it over the index above it (ior entering
/// from the outside, 1 / ior leaving from the inside), as for smooth glass (Scattering.cpp).
///
/// Which radiance scaling: these functions are importance's (Transport::Importance, what light
/// paths carry: power, which refraction does not scale), as the smooth glass's weights are
/// (its refraction weighs 1 - F both ways). Eye paths, which carry radiance, multiply them by
/// Scattering.h's radianceScale, the (eta_wo / eta_wi)^2 of radiance: the same for smooth and
/// rough glass, so an object whose parts are rough and smooth stays consistent.
/// Transport::Radiance is the physical radiance BTDF, which the reciprocity tests check.
namespace roughdielectric {

enum class Transport { Importance, Radiance };

/// Smith G2, height-correlated, of two directions of cosines cosI and cosO with the normal
/// (either sign).
inline float maskingShadowing(float alpha, float cosI, float cosO) {
    const float a2 = alpha * alpha;
    const float ci = std::abs(cosI), co = std::abs(cosO);
    const float denominator = co * ggx::smithRoot(a2, ci) + ci * ggx::smithRoot(a2, co);
    return denominator > 0 ? 2.0f * ci * co / denominator : 0.0f;
}

/// The microfacet normal that takes wo to wi (on wo's side of the microfacet, and facing the
/// macro normal +z of the local frame), and eta' (1 for reflection); false when there is none
/// (grazing directions, wi on the wrong side of its microfacet).
inline bool microfacetNormal(glm::vec3 wo, glm::vec3 wi, float eta, glm::vec3& m, float& etaPrime) {
    const float cosO = wo.z, cosI = wi.z;
    if (!(cosO > 0) || cosI == 0) return false;
    const bool reflected = cosI > 0;
    etaPrime = reflected ? 1.0f : eta;
    const glm::vec3 sum = wi * etaPrime + wo;
    const float len2 = glm::dot(sum, sum);
    if (!(len2 > 0)) return false;
    m = sum / std::sqrt(len2);
    if (m.z < 0) m = -m;
    if (!(m.z > 0)) return false;
    // Back-facing microfacets: wo must be above m, and wi on the side of m where it belongs.
    if (glm::dot(m, wi) * cosI < 0 || glm::dot(m, wo) * cosO <= 0) return false;
    return true;
}

/// f(wo, wi) in the local frame of the normal (+z, wo.z > 0).
inline float evaluateLocal(float alpha, float eta, glm::vec3 wo, glm::vec3 wi,
                           Transport mode = Transport::Importance) {
    glm::vec3 m;
    float etaPrime;
    if (!microfacetNormal(wo, wi, eta, m, etaPrime)) return 0.0f;
    const float cosO = wo.z, cosI = wi.z;
    float cosT = 0;
    const float f = fresnelDielectric(glm::dot(wo, m), eta, cosT);
    const float d = ggx::distribution(alpha, m.z);
    const float g = maskingShadowing(alpha, cosI, cosO);
    if (cosI > 0) return f * d * g / (4.0f * cosI * cosO);
    const float wiM = glm::dot(wi, m), woM = glm::dot(wo, m);
    const float denom = wiM + woM / etaPrime;
    if (!(denom * denom > 0)) return 0.0f;
    float t = (1.0f - f) * d * g * std::abs(wiM * woM / (cosI * cosO * denom * denom));
    if (mode == Transport::Radiance) t /= etaPrime * etaPrime;
    return t;
}

/// The sampler's density (solid angle) of wi given wo, in the local frame.
inline float pdfLocal(float alpha, float eta, glm::vec3 wo, glm::vec3 wi) {
    glm::vec3 m;
    float etaPrime;
    if (!microfacetNormal(wo, wi, eta, m, etaPrime)) return 0.0f;
    float cosT = 0;
    const float woM = glm::dot(wo, m);
    const float r = fresnelDielectric(woM, eta, cosT);
    // Visible normals: G1(wo) D(m) (wo.m) / (n.wo).
    const float visible = ggx::maskingG1(alpha, wo.z) * ggx::distribution(alpha, m.z) * woM / wo.z;
    if (wi.z > 0) return visible / (4.0f * woM) * r;
    const float wiM = glm::dot(wi, m);
    const float denom = wiM + woM / etaPrime;
    if (!(denom * denom > 0)) return 0.0f;
    return visible * std::abs(wiM) / (denom * denom) * (1.0f - r);
}

struct Sample {
    glm::vec3 wi{0.0f};
    float weight = 0;  ///< f |n.wi| / pdf (Transport::Importance): G2 / G1(wo)
    bool refracted = false;
};

/// Samples wi given wo (local frame): false when there is no direction (wo at or below the
/// horizon) or the one drawn is on the wrong side of the macro surface (the energy the single
/// scattering model loses to masking).
inline bool sampleLocal(float alpha, float eta, glm::vec3 wo, glm::vec2 u, float uChoice,
                        Sample& s) {
    if (!(wo.z > 0)) return false;
    const glm::vec3 m = ggx::sampleVisibleNormal(wo, alpha, u);
    const float woM = glm::dot(wo, m);
    if (!(woM > 0)) return false;
    float cosT = 0;
    const float r = fresnelDielectric(woM, eta, cosT);
    if (uChoice < r) {
        s.wi = 2.0f * woM * m - wo;
        s.refracted = false;
        if (!(s.wi.z > 0)) return false;
    } else {
        s.wi = refract(wo, m, eta, cosT);
        s.refracted = true;
        if (!(s.wi.z < 0)) return false;
    }
    s.weight = maskingShadowing(alpha, s.wi.z, wo.z) / ggx::maskingG1(alpha, wo.z);
    return std::isfinite(s.weight);
}

/// The same about a world-space `normal` (wo above it).
inline float evaluate(float alpha, float eta, glm::vec3 normal, glm::vec3 wo, glm::vec3 wi,
                      Transport mode = Transport::Importance) {
    const Frame frame(normal);
    return evaluateLocal(alpha, eta, frame.toLocal(wo), frame.toLocal(wi), mode);
}

inline float pdf(float alpha, float eta, glm::vec3 normal, glm::vec3 wo, glm::vec3 wi) {
    const Frame frame(normal);
    return pdfLocal(alpha, eta, frame.toLocal(wo), frame.toLocal(wi));
}

inline bool sample(float alpha, float eta, glm::vec3 normal, glm::vec3 wo, glm::vec2 u,
                   float uChoice, Sample& s) {
    const Frame frame(normal);
    if (!sampleLocal(alpha, eta, frame.toLocal(wo), u, uChoice, s)) return false;
    s.wi = glm::normalize(frame.toWorld(s.wi));
    return true;
}

}  // namespace roughdielectric
}  // namespace igi
