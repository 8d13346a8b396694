#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include "tracing/TraceableScene.h"

namespace igi {

/// A shadow ray: from a surface point toward another, as a client traces them to VPLs.
struct ShadowSegment {
    glm::vec3 origin;
    glm::vec3 direction;  ///< unit
    float length;
};

/// `count` segments between random points on the scene's surfaces (chosen by area), offset off
/// their surfaces like the renderer's: the raw workload of a client's shadow rays.
std::vector<ShadowSegment> randomShadowSegments(const TraceableScene& scene, std::size_t count,
                                                std::uint64_t seed);

}  // namespace igi
