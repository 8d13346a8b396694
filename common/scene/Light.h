#pragma once

#include <string>

#include <glm/vec3.hpp>

namespace igi {

/// An isotropic point light; `intensity` is radiant intensity (W/sr) per colour channel.
struct PointLight {
    std::string name;
    glm::vec3 position{0.0f};
    glm::vec3 intensity{0.0f};
    bool on = true;  ///< switched off, it emits nothing

    bool operator==(const PointLight&) const = default;
};

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
