#pragma once

#include <algorithm>
#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "scene/Material.h"

namespace igi {

/// Where a ray hit, in world space, with what shading needs.
struct SurfacePoint {
    glm::vec3 position{0.0f};
    glm::vec3 geometricNormal{0.0f};  ///< unit, on the counter-clockwise (front) side
    glm::vec3 shadingNormal{0.0f};    ///< unit, interpolated, same side as geometricNormal
    glm::vec2 uv{0.0f};
    glm::vec3 albedo{0.0f};  ///< Lambertian albedo: Kd times the texture (GGX: the base colour)
    float roughness = 1.0f;  ///< Reflection::Ggx: the factor times the texture's green
    float metallic = 0.0f;   ///< Reflection::Ggx: the factor times the texture's blue
    /// The material's emissive texture at the hit (1 without one): the radiance emitted is
    /// material->emission times this (emittedToward).
    glm::vec3 emissionTexel{1.0f};
    const Material* material = nullptr;
    std::uint32_t mesh = 0;
    std::uint32_t triangle = 0;
    float distance = 0;  ///< along the ray that found it
};

/// Rays traced, for statistics; one per thread, summed per tile.
struct RayCounters {
    std::uint64_t rays = 0;
    std::uint64_t shadowRays = 0;

    RayCounters& operator+=(const RayCounters& o) {
        rays += o.rays;
        shadowRays += o.shadowRays;
        return *this;
    }
    /// One of `parts` equal shares (work done once for all the interleaving sets of a frame,
    /// counted with each set a client builds).
    RayCounters share(std::uint32_t parts) const {
        return {rays / std::max(1u, parts), shadowRays / std::max(1u, parts)};
    }
};

}  // namespace igi
