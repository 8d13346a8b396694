#pragma once

#include <cstdint>
#include <optional>

#include "CameraModel.h"
#include "LightingSet.h"
#include "Lights.h"
#include "PixelResult.h"
#include "PixelSampler.h"
#include "Scattering.h"
#include "TraceableScene.h"
#include "render/RenderSettings.h"

namespace igi {

/// Instant Global Illumination at one pixel (paper, section 4): one eye path, split at its
/// first hit into one continuation per BSDF component; mirrors and glass are followed to a
/// diffuse end point. The end point's irradiance comes from the pixel's set: direct light from
/// the light samples, indirect light from the VPLs, caustics from the photons. The continuation
/// of largest reflectance is the one the master filters; the others are shaded here and sent
/// as unfiltered radiance, with every light seen directly or through mirrors and glass.
class IgiIntegrator {
  public:
    IgiIntegrator(const TraceableScene& scene, const RenderSettings& settings,
                  const CameraModel& camera);

    PixelResult shade(int x, int y, std::uint32_t pixelIndex, std::uint32_t frame,
                      const LightingSet& set, RayCounters& counters) const;

    /// E / pi at a diffuse point lit by `set`, with `normal` facing the viewer (public for tests).
    glm::vec3 irradianceOverPi(glm::vec3 position, glm::vec3 normal, glm::vec3 faceNormal,
                               const LightingSet& set, RayCounters& counters) const;

  private:
    struct EndPoint {
        glm::vec3 position, normal, faceNormal;
        glm::vec3 reflectance;
        float depth;
    };
    std::optional<EndPoint> followSpecular(const SurfacePoint& first, const Lobes& lobes, Lobe lobe,
                                           const PixelSampler& sampler, std::uint32_t firstDim,
                                           glm::vec3& unfiltered, RayCounters& counters) const;

    const TraceableScene& scene_;
    RenderSettings settings_;
    const CameraModel& camera_;
    float clampDistance2_;
};

/// Radiance an emitter sends toward wo from a hit (zero on its back side or if it is no emitter).
glm::vec3 emittedToward(const SurfacePoint& hit, glm::vec3 wo);

}  // namespace igi
