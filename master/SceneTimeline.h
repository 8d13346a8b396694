#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include "Animation.h"
#include "scene/SceneChange.h"
#include "scene/SceneState.h"

namespace igi {

/// Decides the scene state of every frame, as the single source of truth: the scene as loaded,
/// changed by control commands as they arrive and by the animation frame by frame. Each change
/// of state makes a new epoch; a frame renders one epoch from its first tile to its last.
class SceneTimeline {
  public:
    SceneTimeline(SceneState loaded, std::unique_ptr<Animation> animation);

    /// Changes from a control command; they show from the next frame that begins. Throws
    /// std::invalid_argument (and changes nothing) if an index is out of range.
    void control(const std::vector<SceneChange>& changes);

    /// What beginning a frame means for clients: its epoch, and the changes that make it if it
    /// is a new one (empty when the frame renders the same state as the one before).
    struct FrameStart {
        std::uint32_t epoch = 0;
        std::vector<SceneChange> changes;
    };
    FrameStart beginFrame(std::uint32_t frame);

    /// The epoch a begun frame renders.
    std::uint32_t epochOf(std::uint32_t frame) const { return frameEpochs_.at(frame); }
    /// Forgets a finished frame.
    void endFrame(std::uint32_t frame) { frameEpochs_.erase(frame); }

    std::uint32_t epoch() const { return epoch_; }
    const SceneState& state() const { return state_; }
    const SceneState& loaded() const { return loaded_; }
    /// The state control commands apply to: as loaded, plus every command so far.
    const SceneState& controlled() const { return controlled_; }
    /// The changes that bring a freshly loaded scene to the current epoch (for a joining client).
    std::vector<SceneChange> changesSinceLoad() const { return diffStates(loaded_, state_); }

  private:
    SceneState loaded_;
    SceneState controlled_;  ///< loaded + every control change so far
    SceneState state_;       ///< the state of the current epoch
    std::unique_ptr<Animation> animation_;
    std::uint32_t epoch_ = 0;
    std::map<std::uint32_t, std::uint32_t> frameEpochs_;
};

}  // namespace igi
