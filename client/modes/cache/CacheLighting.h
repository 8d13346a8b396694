#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include "lighting/CacheSites.h"
#include "lighting/LightingMethod.h"
#include "lighting/LightingSetBuilder.h"
#include "modes/cache/IrradianceCache.h"
#include "tracing/TraceableScene.h"

namespace igi {

/// Instant caching (paper 003, Debattista et al.) as a GI mode (docs/MODES.md, "Instant
/// caching"): Lambertian end points take the light of the indirect VPLs from irradiance
/// records at object-space sites, interpolated, instead of a shadow ray per VPL per pixel.
///
/// - The frames after a change (accumulation 0) are lit by a VPL collection that is the same
///   in every frame (every set's light paths from fixed numbers): its records are kept for the
///   next epoch, whole when only the camera moved and brought up to date by the paper's
///   Algorithm 1 when objects, lights or materials changed (IrradianceCache). Those frames'
///   sets carry the same VPLs for the glossy end points, so that nothing flickers while
///   nothing changes the light.
/// - Accumulated frames of a still view take the records of that frame's own light paths (IGI's
///   converging estimator's, every set's), computed where pixels need them, so that the
///   accumulated image converges; the compensation, the roulette, the caustics and the direct
///   light are IGI's.
/// Every connection of this mode, cached or not, is bounded by the paper's smooth geometry term
/// (BoundShape::Smooth), so that the compensation restores exactly what the records leave out.
class CacheLighting final : public LightingMethod {
  public:
    CacheLighting(const LightingSetBuilder& builder, const TraceableScene& scene,
                  const SceneState& state, const RenderSettings& settings,
                  const LightingContext& context);

    LightingSet build(std::uint32_t frame, std::uint32_t accumulation,
                      std::uint32_t setIndex) const override;
    std::shared_ptr<const LightingHistory> history(std::uint32_t) const override { return stable_; }

    /// The records of the frames after a change.
    const std::shared_ptr<const IrradianceCache>& stable() const { return stable_; }
    /// The records of accumulated frame `frame` (made on first use).
    std::shared_ptr<const IrradianceCache> frameCache(std::uint32_t frame,
                                                      std::uint32_t accumulation,
                                                      float minDistance2) const;

  private:
    const LightingSetBuilder& builder_;
    const TraceableScene& scene_;
    std::shared_ptr<const SceneState> state_;
    std::uint32_t sets_;
    IrradianceCache::Config config_;
    std::shared_ptr<const CacheSites> sites_;
    std::vector<std::vector<Vpl>> stableSets_;  ///< set k's share of the stable collection
    std::uint32_t stablePaths_ = 0;
    RayCounters stableRays_;  ///< the stable collection's light paths
    std::shared_ptr<const IrradianceCache> stable_;
    mutable std::mutex mutex_;  ///< guards frames_
    mutable std::map<std::uint32_t, std::shared_ptr<const IrradianceCache>> frames_;
};

}  // namespace igi
