#include "SceneTimeline.h"

namespace igi {

SceneTimeline::SceneTimeline(SceneState loaded, std::unique_ptr<Animation> animation)
    : loaded_(loaded),
      controlled_(loaded),
      state_(std::move(loaded)),
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
    }
    start.epoch = epoch_;
    frameEpochs_[frame] = epoch_;
    return start;
}

}  // namespace igi
