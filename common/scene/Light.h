#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>

#include <glm/trigonometric.hpp>
#include <glm/vec3.hpp>

namespace igi {

/// What a punctual light is (the three kinds of glTF's KHR_lights_punctual).
enum class LightKind : std::uint8_t {
    Point,        ///< isotropic, at `position`
    Spot,         ///< at `position`, shining along `direction` within a cone
    Directional,  ///< at infinity, light travelling along `direction` (the sun)
};

/// A light without area: a point, a spot or a directional light. `intensity` is radiant
/// intensity (W/sr) per colour channel for a point or spot light, and irradiance (W/m^2) on a
/// surface that faces it for a directional light.
struct PunctualLight {
    std::string name;
    LightKind kind = LightKind::Point;
    glm::vec3 position{0.0f};                ///< point and spot
    glm::vec3 direction{0.0f, -1.0f, 0.0f};  ///< spot and directional: where the light goes (unit)
    glm::vec3 intensity{0.0f};
    /// Spot: the full-intensity cone and the cone outside which it is dark, half-angles in
    /// degrees, 0 <= inner < outer <= 90; in between the glTF specification's smooth ramp.
    float innerDeg = 0.0f;
    float outerDeg = 45.0f;
    /// Directional: the angular diameter in degrees of the disk it comes from (0: a delta,
    /// 0.53 for the real sun), at most kMaxSunAngleDeg.
    float angleDeg = 0.0f;
    bool on = true;  ///< switched off, it emits nothing

    bool operator==(const PunctualLight&) const = default;
};

/// A point light (tests and defaults build them this way: the struct has more fields).
inline PunctualLight pointLight(std::string name, glm::vec3 position, glm::vec3 intensity,
                                bool on = true) {
    PunctualLight l;
    l.name = std::move(name);
    l.position = position;
    l.intensity = intensity;
    l.on = on;
    return l;
}

/// The glTF specification's ramp of a spot light: the intensity relative to the axis toward a
/// direction at cosine `cosAngle` from it, (clamp((cos - cos outer) * scale, 0, 1))^2 with
/// scale = 1 / (cos inner - cos outer) (spotScale).
inline float spotRamp(float cosOuter, float scale, float cosAngle) {
    const float t = std::clamp((cosAngle - cosOuter) * scale, 0.0f, 1.0f);
    return t * t;
}
inline float spotCosOuter(const PunctualLight& l) {
    return std::cos(glm::radians(l.outerDeg));
}
inline float spotScale(const PunctualLight& l) {
    // The specification's floor on the ramp's width keeps inner == outer finite (a hard edge).
    return 1.0f / std::max(1e-3f, std::cos(glm::radians(l.innerDeg)) - spotCosOuter(l));
}
inline float spotFalloff(const PunctualLight& l, float cosAngle) {
    return spotRamp(spotCosOuter(l), spotScale(l), cosAngle);
}

/// The widest disk a directional light may come from (a wider one is a sky, not a sun).
constexpr float kMaxSunAngleDeg = 30.0f;

/// A one-sided parallelogram area light: points corner + s * edge1 + t * edge2, s, t in [0, 1],
/// emitting `radiance` towards the side of cross(edge1, edge2). It is also visible geometry.
struct QuadLight {
    std::string name;
    glm::vec3 corner{0.0f};
    glm::vec3 edge1{0.0f};
    glm::vec3 edge2{0.0f};
    glm::vec3 radiance{0.0f};
    bool on = true;  ///< switched off, it is a black panel

    bool operator==(const QuadLight&) const = default;
};

}  // namespace igi
