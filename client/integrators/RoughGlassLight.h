#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "lights/Lights.h"
#include "shading/Scattering.h"
#include "tracing/TraceableScene.h"

namespace igi {

/// Which lights a light sample at a rough glass vertex counts.
enum class RoughGlassLights {
    /// Every light, area lights weighed against the BSDF's own sampling by the power heuristic:
    /// the path tracer, whose sampled direction weighs what it hits the other way.
    All,
    /// Only lights that no sampled direction can hit (point, spot, a sun without an angle):
    /// IGI, whose continuation through rough glass adds emitters, the sky and suns whole.
    DeltaOnly,
};

/// One light sample's contribution through rough glass's BSDF at `hit` (`lobes`: its lobes
/// toward the eye), lights on either side of the surface: the shadow ray leaves from the side
/// it goes to. Zero when the sample is not counted (`which`), faces away or is blocked.
glm::vec3 roughGlassLight(const TraceableScene& scene, const Lights& lights,
                          const SurfacePoint& hit, const Lobes& lobes, float uSelect,
                          glm::vec2 uPoint, RoughGlassLights which, RayCounters& counters);

}  // namespace igi
