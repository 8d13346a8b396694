#pragma once

#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "scene/Scene.h"

namespace igi {

/// An axis-aligned box; empty (lo > hi) until a point is added.
struct Bounds3 {
    glm::vec3 lo{std::numeric_limits<float>::infinity()};
    glm::vec3 hi{-std::numeric_limits<float>::infinity()};

    void extend(glm::vec3 p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
    glm::vec3 centre() const { return 0.5f * (lo + hi); }
    /// The scene's scale for the renderer (clamp distance, caustic radius, ray offsets).
    float diagonal() const { return empty() ? 0.0f : glm::length(hi - lo); }
};

/// Bounds of everything in world space: mesh vertices through their transforms, quad lights'
/// corners and point lights' positions.
Bounds3 worldBounds(const Scene& scene);

}  // namespace igi
