#include "SceneTimeline.h"

namespace igi {

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
