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
                             std::uint32_t historyDepth)
    : loaded_(loaded),
      controlled_(loaded),
      state_(loaded),
      historyDepth_(historyDepth),
      base_(std::move(loaded)),
      animation_(std::move(animation)) {}

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
        if (history_.size() > historyDepth_) {
            applyChanges(base_, history_.front().changes);
            baseFirstFrame_ = history_.front().firstFrame;
            ++baseEpoch_;
            history_.pop_front();
        }
    }
    start.epoch = epoch_;
    frameEpochs_[frame] = epoch_;
    return start;
}

SceneTimeline::Join SceneTimeline::join() const {
    Join j;
    j.changes = diffStates(loaded_, base_);
    j.baseFirstFrame = baseFirstFrame_;
    j.history.assign(history_.begin(), history_.end());
    return j;
}

}  // namespace igi
