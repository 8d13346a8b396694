#pragma once

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "math/Frame.h"
#include "math/Warp.h"
#include "scene/Material.h"

namespace igi {

/// The specular lobe of glTF 2.0's metallic-roughness material (the specification's Appendix
/// B): the Trowbridge-Reitz (GGX) distribution D of alpha = roughness^2, the height-correlated
/// Smith visibility V = G2 / (4 |n.wi| |n.wo|) and Schlick's Fresnel of reflectance f0 at
/// normal incidence:
///   f(wi, wo) = F(wo.h) D(n.h) V(n.wi, n.wo),  h = normalize(wi + wo).
/// Directions are unit and point away from the surface, on the side of `normal`. Sampled by
/// the distribution of visible normals (Heitz 2018, "Sampling the GGX Distribution of Visible
/// Normals"), whose density is G1(wo) D(h) / (4 n.wo) and whose weight f cos / pdf is
/// F G2 / G1(wo).
namespace ggx {

/// Below this alpha (roughness 0.0316) a lobe is rendered as a mirror (Material.h).
constexpr float kMinAlpha = kMinGgxAlpha;

inline float distribution(float alpha, float cosH) {
    if (cosH <= 0) return 0.0f;
    const float a2 = alpha * alpha;
    // cos^2 (a^2 - 1) + 1 as sin^2 + a^2 cos^2: near the peak of a smooth lobe (a^2 down to
    // 1e-6) the first form cancels to a few digits; the clamp keeps a rounded cos above 1
    // from making sin^2 negative.
    const float c = std::min(cosH, 1.0f);
    const float d = (1.0f - c) * (1.0f + c) + a2 * c * c;
    return a2 / (kPi * d * d);
}

/// sqrt(a^2 + (1 - a^2) cos^2): the Smith Lambda's square root for one direction.
inline float smithRoot(float a2, float cosTheta) {
    return std::sqrt(a2 + (1.0f - a2) * cosTheta * cosTheta);
}

inline float visibility(float alpha, float cosI, float cosO) {
    const float a2 = alpha * alpha;
    const float denominator = cosO * smithRoot(a2, cosI) + cosI * smithRoot(a2, cosO);
    return denominator > 0 ? 0.5f / denominator : 0.0f;
}

/// G1 of one direction (Smith, GGX): 2 cos / (cos + sqrt(a^2 + (1 - a^2) cos^2)).
inline float maskingG1(float alpha, float cosTheta) {
    return 2.0f * cosTheta / (cosTheta + smithRoot(alpha * alpha, cosTheta));
}

inline glm::vec3 schlick(glm::vec3 f0, float cosVH) {
    const float m = std::clamp(1.0f - std::abs(cosVH), 0.0f, 1.0f);
    const float m2 = m * m;
    return f0 + (glm::vec3(1.0f) - f0) * (m2 * m2 * m);
}

/// The half vector of wi and wo, or false when they are opposite.
inline bool halfVector(glm::vec3 wi, glm::vec3 wo, glm::vec3& h) {
    const glm::vec3 sum = wi + wo;
    const float len = glm::length(sum);
    if (!(len > 0)) return false;
    h = sum / len;
    return true;
}

/// f(wi, wo) of the lobe about `normal`; zero unless both directions are above it.
inline glm::vec3 evaluate(float alpha, glm::vec3 f0, glm::vec3 normal, glm::vec3 wi, glm::vec3 wo) {
    const float cosI = glm::dot(normal, wi), cosO = glm::dot(normal, wo);
    if (cosI <= 0 || cosO <= 0) return glm::vec3(0.0f);
    glm::vec3 h;
    if (!halfVector(wi, wo, h)) return glm::vec3(0.0f);
    return schlick(f0, glm::dot(wo, h)) *
           (distribution(alpha, glm::dot(normal, h)) * visibility(alpha, cosI, cosO));
}

/// The sampler's density (solid angle) of wi given wo.
inline float pdf(float alpha, glm::vec3 normal, glm::vec3 wi, glm::vec3 wo) {
    const float cosI = glm::dot(normal, wi), cosO = glm::dot(normal, wo);
    if (cosI <= 0 || cosO <= 0) return 0.0f;
    glm::vec3 h;
    if (!halfVector(wi, wo, h)) return 0.0f;
    return maskingG1(alpha, cosO) * distribution(alpha, glm::dot(normal, h)) / (4.0f * cosO);
}

/// A microfacet normal from the distribution of normals visible from wo, in the local frame
/// (normal +z; wo.z > 0).
inline glm::vec3 sampleVisibleNormal(glm::vec3 wo, float alpha, glm::vec2 u) {
    const glm::vec3 vh = glm::normalize(glm::vec3(alpha * wo.x, alpha * wo.y, wo.z));
    const float lensq = vh.x * vh.x + vh.y * vh.y;
    const glm::vec3 t1 =
        lensq > 0 ? glm::vec3(-vh.y, vh.x, 0.0f) / std::sqrt(lensq) : glm::vec3(1.0f, 0.0f, 0.0f);
    const glm::vec3 t2 = glm::cross(vh, t1);
    const float r = std::sqrt(u.x);
    const float phi = 2.0f * kPi * u.y;
    const float p1 = r * std::cos(phi);
    const float s = 0.5f * (1.0f + vh.z);
    const float p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * r * std::sin(phi);
    const glm::vec3 nh =
        p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
    return glm::normalize(glm::vec3(alpha * nh.x, alpha * nh.y, std::max(1e-6f, nh.z)));
}

/// A direction wi reflected about a visible normal; may lie below the surface (then the
/// caller rejects it: the lobe's energy lost to masking is what it misses).
inline glm::vec3 sample(float alpha, glm::vec3 normal, glm::vec3 wo, glm::vec2 u) {
    const Frame frame(normal);
    const glm::vec3 woLocal = frame.toLocal(wo);
    if (woLocal.z <= 0) return -normal;
    const glm::vec3 h = frame.toWorld(sampleVisibleNormal(woLocal, alpha, u));
    return 2.0f * glm::dot(wo, h) * h - wo;
}

/// The cap of sharpness(): four times its peak at normal incidence, 1 / (4 alpha^2). It must
/// bound sharpness() everywhere: the compensation's reach is computed from it.
inline float maxSharpness(float alpha) {
    return 1.0f / (alpha * alpha);
}

/// pi D V for the pair, capped at maxSharpness(alpha): the lobe's sharpness for the bound on
/// VPL connections (client/shading/ConnectionBound.h), pi times f normalized to unit reflectance (V
/// grows without bound at grazing angles, where f cos stays finite). Exactly symmetric in wi
/// and wo, so that both ends of a connection, and its compensation, agree on it.
inline float sharpness(float alpha, glm::vec3 normal, glm::vec3 wi, glm::vec3 wo) {
    const float cosI = glm::dot(normal, wi), cosO = glm::dot(normal, wo);
    if (cosI <= 0 || cosO <= 0) return 0.0f;
    glm::vec3 h;
    if (!halfVector(wi, wo, h)) return 0.0f;
    const float s = kPi * distribution(alpha, glm::dot(normal, h)) * visibility(alpha, cosI, cosO);
    return std::min(s, maxSharpness(alpha));
}

}  // namespace ggx
}  // namespace igi
