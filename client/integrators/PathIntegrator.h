#pragma once

#include <cstdint>

#include "lights/Lights.h"
#include "render/RenderSettings.h"
#include "scene/CameraModel.h"
#include "shading/Scattering.h"
#include "tracing/TraceableScene.h"

namespace igi {

/// The brute-force reference: unidirectional path tracing over the same scene and materials,
/// with next-event estimation on the non-delta lobes (Lambertian and glossy; multiple importance
/// sampling against BRDF sampling for area lights) and Russian roulette. Mirror and smooth glass
/// bounces are sampled only; rough glass (a GGX BSDF) has light samples and MIS as well. Converges
/// to the answer IGI approximates.
class PathIntegrator {
  public:
    PathIntegrator(const TraceableScene& scene, const Lights& lights,
                   const RenderSettings& settings, const CameraModel& camera);

    /// Mean radiance of settings.pathSamples paths through the pixel in this frame.
    glm::vec3 shade(int x, int y, std::uint32_t pixelIndex, std::uint32_t frame,
                    RayCounters& counters) const;

  private:
    glm::vec3 tracePath(int x, int y, std::uint32_t pixelIndex, std::uint32_t sampleIndex,
                        RayCounters& counters) const;
    /// The light samples' contribution through the non-delta BRDF, MIS-weighted: one light
    /// chosen by uSelect, and each exact light (Lights::exactLight).
    glm::vec3 directLight(const SurfacePoint& hit, const Lobes& lobes, float uSelect,
                          glm::vec2 uPoint, RayCounters& counters) const;
    /// One light sample's contribution, as directLight's.
    glm::vec3 lightSample(const SurfacePoint& hit, const Lobes& lobes, const LightSample& ls,
                          RayCounters& counters) const;

    const TraceableScene& scene_;
    const Lights& lights_;
    RenderSettings settings_;
    const CameraModel& camera_;
};

}  // namespace igi
