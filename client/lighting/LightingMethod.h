#pragma once

#include <cstdint>
#include <memory>

#include "lighting/LightingSet.h"

namespace igi {

struct Scene;

/// What a method that keeps lighting across frames hands from one scene epoch to the next
/// (photon streaming's pool). Immutable once made: tiles of an older epoch keep theirs.
struct LightingHistory {
    virtual ~LightingHistory() = default;
};

/// How a client lights the frames of one scene epoch: the family of GI methods the cluster runs
/// (RenderSettings::gi), each in its own files behind this interface. A method builds the set
/// P_k / C_k of interleaving identification k from nothing but the session's seed and
/// settings, the frame, the frame's place in its accumulation and the scene's history of
/// epochs, so that every client builds the same set and the image does not depend on which
/// client rendered what. The integrator, the wire, the scheduler and the discontinuity buffer
/// are the same for all.
///
/// Every method lights the accumulated frames of a still view (accumulation > 0) as IGI's
/// converging estimator does, so that every mode converges to the same answer; they differ in
/// what the frames right after a change show, which is what they were made for.
class LightingMethod {
  public:
    virtual ~LightingMethod() = default;

    virtual LightingSet build(std::uint32_t frame, std::uint32_t accumulation,
                              std::uint32_t setIndex) const = 0;

    /// The state the next epoch's method starts from, that epoch beginning at frame
    /// `nextFirstFrame` (null for methods without one).
    virtual std::shared_ptr<const LightingHistory> history(std::uint32_t nextFirstFrame) const {
        (void)nextFirstFrame;
        return nullptr;
    }
};

/// What making a method needs beyond one scene version.
struct LightingContext {
    const Scene* scene = nullptr;  ///< the scene as loaded (meshes, for surface lights)
    std::uint32_t epoch = 0;
    /// The epoch's first frame (the frame of its SceneUpdate): methods that go on working
    /// while the scene holds still count their steps from it.
    std::uint32_t firstFrame = 0;
    /// The previous epoch's history, or null for the first epoch this client has.
    std::shared_ptr<const LightingHistory> previous;
};

}  // namespace igi
