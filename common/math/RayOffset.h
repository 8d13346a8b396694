#pragma once

#include <bit>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace igi {

/// Moves a ray origin off the surface it starts on, along the geometric normal `n` (pointing to
/// the side the ray leaves to). The offset is a few float ULPs of the point's own coordinates
/// (Waechter and Binder, Ray Tracing Gems, ch. 6), so it is right at every scene scale: an
/// absolute epsilon breaks for tiny scenes and for points far from the origin. Coordinates near
/// zero, where ULPs vanish, get a fixed fraction of `sceneScale` (the scene's bounding-box
/// diagonal) instead: the hit point's error there is relative to the scene's vertices.
inline glm::vec3 offsetRayOrigin(glm::vec3 p, glm::vec3 n, float sceneScale) {
    constexpr float kOrigin = 1.0f / 32.0f;
    constexpr float kFloatScale = 1.0f / 65536.0f;
    constexpr float kIntScale = 256.0f;
    glm::vec3 result;
    for (int i = 0; i < 3; ++i) {
        const auto offset = static_cast<std::int32_t>(kIntScale * n[i]);
        const auto bits = std::bit_cast<std::int32_t>(p[i]);
        const float moved = std::bit_cast<float>(bits + (p[i] < 0 ? -offset : offset));
        result[i] =
            std::fabs(p[i]) < kOrigin * sceneScale ? p[i] + kFloatScale * sceneScale * n[i] : moved;
    }
    return result;
}

/// Offsets toward the side of `n` that `direction` leaves to.
inline glm::vec3 offsetRayOrigin(glm::vec3 p, glm::vec3 n, glm::vec3 direction, float sceneScale) {
    return offsetRayOrigin(p, glm::dot(direction, n) >= 0 ? n : -n, sceneScale);
}

}  // namespace igi
