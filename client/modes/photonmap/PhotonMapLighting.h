#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include "lighting/CacheSites.h"
#include "lighting/LightingMethod.h"
#include "lighting/LightingSetBuilder.h"
#include "modes/photonmap/PhotonEmission.h"
#include "modes/photonmap/PhotonMapCache.h"
#include "modes/photonmap/ScreenCaustics.h"
#include "scene/Scene.h"
#include "tracing/TraceableScene.h"

namespace igi {

/// What simulated photon mapping hands from one epoch to the next: the emission at the frame
/// before, and the reconstruction made from it (kept whole when only the camera moved).
struct PhotonMapHistory final : LightingHistory {
    std::shared_ptr<const PhotonEmission> emission;
    std::shared_ptr<const PhotonMapCache> cache;
};

/// Larsen and Christensen's simulated photon mapping (paper 002) as a GI mode (docs/MODES.md,
/// "Simulated photon mapping"). The frames after a change (accumulation 0) are lit by
/// - direct light: the set's light samples, as IGI's (shadow rays);
/// - indirect light: the photons of selective photon emission (PhotonEmission: groups, one
///   photon of each retraced per frame round robin, a group that diverged retraced whole),
///   reconstructed at the cache sites (PhotonMapCache: the photon map's radiance, then a final
///   gather from it) and interpolated at the pixels; a glossy lobe takes the reconstructed
///   radiance of what its continuation ray meets;
/// - caustics: the frame's caustic photons filtered in screen space (ScreenCaustics), or, with
///   photonmap_caustics "grid", gathered from IGI's hashed grid.
/// Accumulated frames of a still view are IGI's converging estimator (LightingMethod).
class PhotonMapLighting final : public LightingMethod {
  public:
    PhotonMapLighting(const LightingSetBuilder& builder, const TraceableScene& scene,
                      const SceneState& state, const RenderSettings& settings,
                      const ImageSettings& image, const LightingContext& context);

    LightingSet build(std::uint32_t frame, std::uint32_t accumulation,
                      std::uint32_t setIndex) const override;
    std::shared_ptr<const LightingHistory> history(std::uint32_t nextFirstFrame) const override;

    /// The emission at `frame` of this epoch (frames before its first: the first's).
    std::shared_ptr<const PhotonEmission> emissionAt(std::uint32_t frame) const;
    std::shared_ptr<const PhotonMapCache> cacheAt(std::uint32_t frame) const;
    std::shared_ptr<const ScreenCaustics> screenCaustics(std::uint32_t frame) const;

  private:
    struct Step {
        std::size_t index = 0;  ///< made for frame firstFrame_ + index
        std::shared_ptr<const PhotonEmission> emission;
        std::shared_ptr<const PhotonMapCache> cache;
    };
    std::shared_ptr<const Step> stepAt(std::uint32_t frame) const;
    /// The reconstruction of `emission`: `reuse`'s records when it holds the same photons in a
    /// state lit the same way, else new ones.
    std::shared_ptr<const PhotonMapCache> reconstruct(
        const std::shared_ptr<const PhotonEmission>& emission,
        const std::shared_ptr<const PhotonMapCache>& reuse, std::uint64_t reuseVersion) const;

    const LightingSetBuilder& builder_;
    const TraceableScene& scene_;
    std::shared_ptr<const SceneState> state_;
    ImageSettings image_;
    EmissionTracer tracer_;
    std::uint32_t firstFrame_;
    std::uint32_t sets_;
    bool screen_;
    std::shared_ptr<const CacheSites> sites_;
    PhotonMapCache::Config config_;
    int neighbours_;
    mutable std::mutex mutex_;  ///< guards steps_ and screens_
    /// The last kKeptSteps frames' steps (those of frames from firstFrame_ + stepsBase_ on): a
    /// step may hold a photon map and a reconstruction of its own, and the master has only a
    /// few frames in flight.
    mutable std::deque<std::shared_ptr<const Step>> steps_;
    mutable std::size_t stepsBase_ = 0;
    mutable std::map<std::uint32_t, std::shared_ptr<const ScreenCaustics>> screens_;
};

}  // namespace igi
