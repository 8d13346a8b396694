#pragma once

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace igi {

/// An orthonormal basis around a unit normal (Duff et al. 2017, branchless and continuous
/// except at one point), to turn local sample directions into world directions.
struct Frame {
    glm::vec3 s, t, n;

    explicit Frame(glm::vec3 normal) : n(normal) {
        const float sign = std::copysign(1.0f, n.z);
        const float a = -1.0f / (sign + n.z);
        const float b = n.x * n.y * a;
        s = glm::vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
        t = glm::vec3(b, sign + n.y * n.y * a, -n.y);
    }

    glm::vec3 toWorld(glm::vec3 local) const { return s * local.x + t * local.y + n * local.z; }
    glm::vec3 toLocal(glm::vec3 world) const {
        return {glm::dot(world, s), glm::dot(world, t), glm::dot(world, n)};
    }
};

}  // namespace igi
