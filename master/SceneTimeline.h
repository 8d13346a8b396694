#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <vector>

#include "Animation.h"
#include "render/RenderSettings.h"
#include "scene/SceneChange.h"
#include "scene/SceneState.h"

namespace igi {

/// The epochs of history a joining client replays to hold the lighting the others hold, for
/// the GI mode of `settings` (the `historyDepth` of a SceneTimeline).
std::uint32_t joinHistoryDepth(const RenderSettings& settings);

/// Decides the scene state of every frame, as the single source of truth: the scene as loaded,
/// changed by control commands as they arrive and by the animation frame by frame. Each change
/// of state makes a new epoch; a frame renders one epoch from its first tile to its last.
class SceneTimeline {
  public:
    /// `historyDepth`: how many of the latest epochs' changes to keep for joining clients (GI
    /// modes that keep lighting across epochs replay them, docs/MODES.md).
    /// `firstFrame`: the session's first frame (MasterOptions::firstFrame), where epoch 0
    /// begins; past 0, epoch 0 is the animation's state at that frame.
    SceneTimeline(SceneState loaded, std::unique_ptr<Animation> animation,
                  std::uint32_t historyDepth = 0, std::uint32_t firstFrame = 0);

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
    /// Forgets a finished frame: a joiner no longer needs its epoch.
    void endFrame(std::uint32_t frame);

    std::uint32_t epoch() const { return epoch_; }
    const SceneState& state() const { return state_; }
    const SceneState& loaded() const { return loaded_; }
    /// The state control commands apply to: as loaded, plus every command so far.
    const SceneState& controlled() const { return controlled_; }
    /// One epoch after the base: the frame it began at and the changes that made it.
    struct Epoch {
        std::uint32_t firstFrame = 0;
        std::vector<SceneChange> changes;
    };
    /// What a joining client needs: the changes that bring a freshly loaded scene to the base
    /// epoch, the frame the base began at, and the epochs since. The base is historyDepth
    /// epochs back (not past the last settings change), or the epoch of the oldest frame still
    /// open if that is older: a joiner may be given any tile of an open frame, whichever epoch
    /// it renders, when the client holding it leaves.
    struct Join {
        std::vector<SceneChange> changes;
        std::uint32_t baseFirstFrame = 0;
        std::vector<Epoch> history;
    };
    Join join() const;
    /// Whether the history kept reaches back to where the lighting started: the loaded scene
    /// (epoch 0) or the last change of the render settings, from which every client starts
    /// afresh.
    bool historyComplete() const { return baseEpoch_ <= restartEpoch_; }
    /// The oldest epoch a joiner gets (the Join's base).
    std::uint32_t baseEpoch() const { return baseEpoch_; }
    /// The oldest epoch a client that joins now holds: the base and those after it, at most
    /// the newest proto::kClientKeptEpochs.
    std::uint32_t oldestEpochAJoinerHolds() const;

  private:
    /// Moves the base forward, past the epochs no joiner needs any more (see Join).
    void forgetOldEpochs();

    SceneState loaded_;
    SceneState controlled_;  ///< loaded + every control change so far
    SceneState state_;       ///< the state of the current epoch
    std::uint32_t historyDepth_;
    SceneState base_;  ///< the state of the oldest epoch whose successors are kept
    std::uint32_t baseEpoch_ = 0, baseFirstFrame_ = 0;
    std::uint32_t restartEpoch_ = 0;  ///< epoch 0, or the last that changed the settings
    std::deque<Epoch> history_;       ///< the epochs after the base, oldest first
    std::unique_ptr<Animation> animation_;
    std::uint32_t epoch_ = 0;
    std::map<std::uint32_t, std::uint32_t> frameEpochs_;
};

}  // namespace igi
