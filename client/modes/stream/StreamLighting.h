#pragma once

#include <memory>
#include <vector>

#include "lighting/LightingMethod.h"
#include "lighting/LightingSetBuilder.h"
#include "lights/SurfaceLights.h"
#include "modes/stream/PhotonStream.h"
#include "tracing/TraceableScene.h"

namespace igi {

/// Photon streaming (paper 001, Meneveaux and Bridault 2008) as a GI mode: the first frame of
/// an epoch takes its indirect light from the VSLs of the epoch's photon pool (PhotonStream),
/// its direct light and caustics as IGI's first frame does. Unlike the paper, VSLs are shaded
/// with visibility (a shadow ray each, as IGI's VPLs, bounded by the same clamp) and are split
/// among the interleaving sets (VSL i lights set i mod K, K times as bright), so a pixel
/// costs what an IGI pixel costs and the discontinuity buffer puts the sets back together.
/// Accumulated frames of a still view are IGI's converging estimator (LightingMethod).
class StreamLighting final : public LightingMethod {
  public:
    /// The method of one epoch: its scene and builder, and the previous epoch's pool in
    /// `context` (or null: the client's first epoch, whose pool it fills).
    StreamLighting(const LightingSetBuilder& builder, const TraceableScene& scene,
                   const SceneState& state, const RenderSettings& settings,
                   const LightingContext& context);

    LightingSet build(std::uint32_t frame, std::uint32_t accumulation,
                      std::uint32_t setIndex) const override;
    std::shared_ptr<const LightingHistory> history(std::uint32_t) const override { return stream_; }

    const PhotonStream& stream() const { return *stream_; }
    /// The VSLs as placed in this epoch's state.
    const std::vector<SurfaceLight>& lights() const { return lights_; }
    /// Rays traced to shoot this epoch's batch (all of the pool's for a first epoch).
    const RayCounters& shootRays() const { return shootRays_; }

  private:
    const LightingSetBuilder& builder_;
    const TraceableScene& scene_;
    std::uint32_t firstFrame_;
    std::vector<SurfaceLight> lights_;
    std::shared_ptr<const PhotonStream> stream_;
    std::vector<std::vector<Vpl>> setVpls_;  ///< the VSLs as lights; set k has VSLs i % K == k
    RayCounters shootRays_;
};

}  // namespace igi
