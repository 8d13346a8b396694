#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace igi {

/// What a ray that leaves the scene sees: a constant sky or an equirectangular map, light from
/// every direction at infinity. Absent (black) by default.
struct Environment {
    /// Radiance W/(m^2 sr) per channel of a constant sky; with a map, the factor it is scaled by.
    glm::vec3 radiance{0.0f};
    int texture = -1;  ///< the equirectangular map in Scene::textures, or -1
    /// Turns the sky about the up axis (+Y), right-handed, in degrees.
    float rotateDeg = 0.0f;

    bool present() const { return radiance.x > 0 || radiance.y > 0 || radiance.z > 0; }
    bool operator==(const Environment&) const = default;
};

/// The equirectangular map's coordinates of a unit direction in the sky's own frame, oriented as
/// Blender's Environment Texture node with the glTF importer's axes (Y up here, Z up there):
/// the image's centre (u = 0.5) looks along +X, +Z is at u = 0.75, the top row (v = 0) is
/// straight up. u in [0, 1), v in [0, 1], v counted from the top.
inline glm::vec2 equirectUv(glm::vec3 d) {
    constexpr float kTwoPi = 2.0f * std::numbers::pi_v<float>;
    float u = 0.5f + std::atan2(d.z, d.x) / kTwoPi;
    if (u >= 1.0f) u -= 1.0f;
    const float v = std::acos(std::clamp(d.y, -1.0f, 1.0f)) / std::numbers::pi_v<float>;
    return {std::max(u, 0.0f), v};
}

/// The inverse of equirectUv.
inline glm::vec3 equirectDirection(glm::vec2 uv) {
    constexpr float kPi = std::numbers::pi_v<float>;
    const float phi = (uv.x - 0.5f) * 2.0f * kPi, theta = uv.y * kPi;
    const float s = std::sin(theta);
    return {s * std::cos(phi), std::cos(theta), s * std::sin(phi)};
}

/// A direction turned by `deg` about +Y (right-handed).
inline glm::vec3 turnAboutUp(glm::vec3 d, float deg) {
    const float a = deg * (std::numbers::pi_v<float> / 180.0f);
    const float c = std::cos(a), s = std::sin(a);
    return {c * d.x + s * d.z, d.y, -s * d.x + c * d.z};
}

}  // namespace igi
