#include "SceneTimeline.h"

#include <algorithm>

#include "Messages.h"

namespace igi {

// Photon streaming's pool spans the last stream_window epochs (the oldest of which a joiner
// fills whole, as every client filled epoch 0); selective photon tracing's depends on every
// epoch since the session began, and so does simulated photon mapping's emission (each frame
// checks photons round robin); IGI keeps nothing, and instant caching's records are a function
// of the current state alone (a joiner computes them anew, to the same bits).
std::uint32_t joinHistoryDepth(const RenderSettings& s) {
    if (s.integrator == IntegratorKind::Path) return 0;
    switch (s.gi) {
        case GiMode::Stream:
            return std::uint32_t(std::max(0, s.streamWindow - 1));
        case GiMode::Spt:
        case GiMode::PhotonMap:
            return proto::kMaxHistoryEpochs;
        case GiMode::Igi:
        case GiMode::Cache:
            break;
    }
    return 0;
}

SceneTimeline::SceneTimeline(SceneState loaded, std::unique_ptr<Animation> animation,
                             std::uint32_t historyDepth, std::uint32_t firstFrame)
    : loaded_(loaded),
      controlled_(loaded),
      state_(loaded),
      historyDepth_(historyDepth),
      base_(std::move(loaded)),
      baseFirstFrame_(firstFrame),
      animation_(std::move(animation)) {
    // A session started at a later frame starts in the state its animation gives that frame,
    // as epoch 0: as a session started there with that scene would (no epoch of the frames it
    // skipped, no lighting kept from them).
    if (animation_ && firstFrame > 0) state_ = base_ = animation_->stateAt(firstFrame, loaded_);
}

void SceneTimeline::control(const std::vector<SceneChange>& changes) {
    applyChanges(controlled_, changes);
}

SceneTimeline::FrameStart SceneTimeline::beginFrame(std::uint32_t frame) {
    // The animation sets what it animates; control commands keep everything else.
    const SceneState wanted = animation_ ? animation_->stateAt(frame, controlled_) : controlled_;
    FrameStart start;
    start.changes = diffStates(state_, wanted);
    if (!start.changes.empty()) {
        ++epoch_;
        state_ = wanted;
        history_.push_back({frame, start.changes});
        if (changesSettings(start.changes)) {
            // Clients start the lighting afresh at new settings (a session started with them
            // here would have no past); the new settings may keep more or less of what follows.
            restartEpoch_ = epoch_;
            historyDepth_ = joinHistoryDepth(state_.render);
        }
    }
    start.epoch = epoch_;
    frameEpochs_[frame] = epoch_;
    forgetOldEpochs();
    return start;
}

void SceneTimeline::endFrame(std::uint32_t frame) {
    frameEpochs_.erase(frame);
    forgetOldEpochs();
}

void SceneTimeline::forgetOldEpochs() {
    // What the GI mode's lighting depends on: historyDepth epochs, none before new settings.
    std::uint32_t needed =
        std::max<std::int64_t>(restartEpoch_, std::int64_t(epoch_) - historyDepth_);
    // Frames open at an older epoch may still need a client for their tiles; frames open in
    // order, so the first holds the oldest epoch.
    if (!frameEpochs_.empty()) needed = std::min(needed, frameEpochs_.begin()->second);
    while (baseEpoch_ < needed) {
        applyChanges(base_, history_.front().changes);
        baseFirstFrame_ = history_.front().firstFrame;
        ++baseEpoch_;
        history_.pop_front();
    }
}

SceneTimeline::Join SceneTimeline::join() const {
    Join j;
    j.changes = diffStates(loaded_, base_);
    j.baseFirstFrame = baseFirstFrame_;
    j.history.assign(history_.begin(), history_.end());
    return j;
}

std::uint32_t SceneTimeline::oldestEpochAJoinerHolds() const {
    return std::uint32_t(
        std::max<std::int64_t>(baseEpoch_, std::int64_t(epoch_) - proto::kClientKeptEpochs + 1));
}

}  // namespace igi
