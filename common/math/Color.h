#pragma once

#include <algorithm>
#include <cmath>

#include <glm/ext/vector_double3.hpp>
#include <glm/vec3.hpp>

namespace igi {

inline float luminance(glm::vec3 c) {
    return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}
/// In double, for sums of many frames.
inline double luminance(const glm::dvec3& c) {
    return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
}
inline float maxComponent(glm::vec3 c) {
    return std::max(c.x, std::max(c.y, c.z));
}
inline float meanComponent(glm::vec3 c) {
    return (c.x + c.y + c.z) * (1.0f / 3.0f);
}
inline bool isBlack(glm::vec3 c) {
    return c.x <= 0 && c.y <= 0 && c.z <= 0;
}
inline bool isFinite(glm::vec3 c) {
    return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z);
}

}  // namespace igi
