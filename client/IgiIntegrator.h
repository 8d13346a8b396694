#pragma once

#include <cstdint>
#include <optional>

#include "scene/CameraModel.h"
#include "DeltaChain.h"
#include "EndPointShader.h"
#include "LightingSet.h"
#include "Lights.h"
#include "PixelResult.h"
#include "PixelSampler.h"
#include "TraceableScene.h"
#include "render/RenderSettings.h"

namespace igi {

/// Instant Global Illumination at one pixel (paper, section 4): one eye path, split at its
/// first hit into its non-delta part (Lambertian and glossy, shaded there) and one path per
/// delta component (mirror, glass), followed to a non-delta end point. Each end point is
/// shaded by the EndPointShader with the pixel's set. The end point of largest reflectance is
/// the one the master filters (its irradiance and its glossy radiance); the others are sent as
/// unfiltered radiance, with every light seen directly or through mirrors and glass.
class IgiIntegrator {
  public:
    IgiIntegrator(const TraceableScene& scene, const Lights& lights, const RenderSettings& settings,
                  const CameraModel& camera);

    PixelResult shade(int x, int y, std::uint32_t pixelIndex, std::uint32_t frame,
                      const LightingSet& set, RayCounters& counters) const;

    /// E / pi at a Lambertian point lit by `set`, with `normal` facing the viewer, without any
    /// continuation ray (public for tests).
    glm::vec3 irradianceOverPi(glm::vec3 position, glm::vec3 normal, glm::vec3 faceNormal,
                               const LightingSet& set, RayCounters& counters) const;

  private:
    const TraceableScene& scene_;
    RenderSettings settings_;
    const CameraModel& camera_;
    EndPointShader shader_;
};

}  // namespace igi
