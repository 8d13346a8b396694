#pragma once

#include <memory>
#include <mutex>
#include <vector>

#include "lighting/LightingMethod.h"
#include "lighting/LightingSetBuilder.h"
#include "modes/spt/PhotonGroups.h"

namespace igi {

/// Selective photon tracing (paper 000, Dmitriev et al. 2002) as a GI mode: a pool of
/// sptGroups x sptPaths light paths from a Halton sequence, grouped by its periodicity
/// (PhotonGroups). A scene change marks the groups it touches (their own paths hit a moved
/// object, or their pilots, traced on the new scene, do; any light or material change touches
/// all); each frame traces at most sptBudget marked groups again, the oldest first, also
/// while the scene then holds still; the other groups keep their light. The first frame of an
/// epoch (and every frame without accumulation) takes its indirect light from the pool's VPLs,
/// its direct light and caustics as IGI's first frame does. VPL i of group g lights set
/// (g P + i's path) mod K with K times its power, so a pixel costs what an IGI pixel does for
/// the same number of VPLs. Accumulated frames are IGI's converging estimator.
class SelectiveLighting final : public LightingMethod {
  public:
    /// The method of one epoch, which begins at context.firstFrame; context.previous is the
    /// pool at the frame before (or null: the client's first epoch, whose pool it traces).
    SelectiveLighting(const LightingSetBuilder& builder, const SceneState& state,
                      const RenderSettings& settings, const LightingContext& context);

    LightingSet build(std::uint32_t frame, std::uint32_t accumulation,
                      std::uint32_t setIndex) const override;
    std::shared_ptr<const LightingHistory> history(std::uint32_t nextFirstFrame) const override;

    /// The pool at `frame` of this epoch (frames before its first: the first's).
    std::shared_ptr<const PhotonGroups> poolAt(std::uint32_t frame) const;
    std::uint32_t firstFrame() const { return firstFrame_; }

  private:
    struct Step {
        std::size_t index = 0;  ///< made for frame firstFrame_ + index
        std::shared_ptr<const PhotonGroups> pool;
        std::vector<std::vector<Vpl>> sets;  ///< the pool's VPLs split among the K sets
    };
    std::shared_ptr<const Step> stepAt(std::uint32_t frame) const;
    std::shared_ptr<const Step> makeStep(std::size_t index,
                                         std::shared_ptr<const PhotonGroups> pool) const;

    const LightingSetBuilder& builder_;
    GroupTracer tracer_;
    std::uint32_t firstFrame_;
    std::uint32_t budget_, pathsPerGroup_, sets_;
    mutable std::mutex mutex_;  ///< guards steps_
    /// steps_[j]: frame firstFrame_ + j; the last one holds for every later frame once no
    /// group waits.
    mutable std::vector<std::shared_ptr<const Step>> steps_;
};

}  // namespace igi
