#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace igi {

constexpr float kPi = std::numbers::pi_v<float>;
constexpr float kInvPi = 1.0f / kPi;

/// Maps of the unit square to directions and points, each with its density.

/// A uniform point on the unit disk (Shirley and Chiu's concentric map); pdf 1/pi.
inline glm::vec2 squareToUniformDisk(glm::vec2 u) {
    const float a = 2.0f * u.x - 1.0f, b = 2.0f * u.y - 1.0f;
    float r = 0, phi = 0;
    if (a != 0 || b != 0) {
        if (a * a > b * b) {
            r = a;
            phi = (kPi / 4) * (b / a);
        } else {
            r = b;
            phi = (kPi / 2) - (kPi / 4) * (a / b);
        }
    }
    return {r * std::cos(phi), r * std::sin(phi)};
}

/// Cosine-weighted direction about +Z (Malley's method on a concentric disk); pdf cos/pi.
inline glm::vec3 squareToCosineHemisphere(glm::vec2 u) {
    const glm::vec2 d = squareToUniformDisk(u);
    return {d.x, d.y, std::sqrt(std::max(0.0f, 1.0f - d.x * d.x - d.y * d.y))};
}

/// Uniform direction on the sphere; pdf 1/(4 pi).
inline glm::vec3 squareToUniformSphere(glm::vec2 u) {
    const float z = 1.0f - 2.0f * u.x;
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float phi = 2.0f * kPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

/// Uniform direction in the cone of half-angle acos(cosMax) about +Z; pdf 1/(2 pi (1-cosMax)).
/// Not for narrow cones: a float cosMax near 1 keeps few digits of 1 - cosMax (none below a
/// half-angle of 2.4e-4 rad); CausticShooter keeps 1 - cos itself, computed from the sine.
inline glm::vec3 squareToUniformCone(glm::vec2 u, float cosMax) {
    const float z = 1.0f - u.x * (1.0f - cosMax);
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float phi = 2.0f * kPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

inline float uniformConePdf(float cosMax) {
    return 1.0f / (2.0f * kPi * (1.0f - cosMax));
}

/// Barycentric coordinates (b1, b2) of a uniform point on a triangle.
inline glm::vec2 squareToUniformTriangle(glm::vec2 u) {
    const float su = std::sqrt(u.x);
    return {1.0f - su, u.y * su};
}

/// A direction about +Z distributed as cos^exponent (the normalized Phong lobe sampling).
inline glm::vec3 squareToPhongLobe(glm::vec2 u, float exponent) {
    const float cosTheta = std::pow(1.0f - u.x, 1.0f / (exponent + 1.0f));
    const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
    const float phi = 2.0f * kPi * u.y;
    return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}

}  // namespace igi
