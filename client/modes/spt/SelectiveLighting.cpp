#include "modes/spt/SelectiveLighting.h"

#include <algorithm>
#include <stdexcept>

namespace igi {

SelectiveLighting::SelectiveLighting(const LightingSetBuilder& builder, const SceneState& state,
                                     const RenderSettings& settings, const LightingContext& context)
    : builder_(builder),
      tracer_(builder, std::make_shared<const SceneState>(state), settings),
      firstFrame_(context.firstFrame),
      budget_(std::uint32_t(std::max(1, settings.sptBudget))),
      pathsPerGroup_(std::uint32_t(std::max(1, settings.sptPaths))),
      sets_(std::uint32_t(std::max(1, settings.setCount()))) {
    auto previous = std::dynamic_pointer_cast<const PhotonGroups>(context.previous);
    if (context.previous && !previous)
        throw std::invalid_argument("selective photon tracing continues another method's state");
    auto pool = previous ? previous->change(tracer_, firstFrame_, budget_)
                         : PhotonGroups::traceAll(tracer_, firstFrame_);
    steps_.push_back(makeStep(0, std::move(pool)));
}

std::shared_ptr<const SelectiveLighting::Step> SelectiveLighting::makeStep(
    std::size_t index, std::shared_ptr<const PhotonGroups> pool) const {
    auto step = std::make_shared<Step>();
    step->index = index;
    step->sets.resize(sets_);
    const float share = float(sets_);
    for (const auto& group : pool->groups()) {
        for (std::size_t i = 0; i < group->vpls.size(); ++i) {
            Vpl v = group->vpls[i];
            v.power *= share;
            v.glossyPower *= share;
            step->sets[(group->index * pathsPerGroup_ + group->vplPaths[i]) % sets_].push_back(v);
        }
    }
    step->pool = std::move(pool);
    return step;
}

std::shared_ptr<const SelectiveLighting::Step> SelectiveLighting::stepAt(
    std::uint32_t frame) const {
    const std::size_t j = frame > firstFrame_ ? frame - firstFrame_ : 0;
    std::lock_guard lock(mutex_);
    // Each frame's pool from the one before, in frame order, until no group waits: the pool of
    // a frame does not depend on which frames this client rendered.
    while (steps_.size() <= j && steps_.back()->pool->invalidCount() > 0) {
        const auto next = std::uint32_t(firstFrame_ + steps_.size());
        steps_.push_back(
            makeStep(steps_.size(), steps_.back()->pool->step(tracer_, next, budget_)));
    }
    return steps_[std::min(j, steps_.size() - 1)];
}

std::shared_ptr<const PhotonGroups> SelectiveLighting::poolAt(std::uint32_t frame) const {
    return stepAt(frame)->pool;
}

std::shared_ptr<const LightingHistory> SelectiveLighting::history(
    std::uint32_t nextFirstFrame) const {
    return poolAt(nextFirstFrame > firstFrame_ ? nextFirstFrame - 1 : firstFrame_);
}

LightingSet SelectiveLighting::build(std::uint32_t frame, std::uint32_t accumulation,
                                     std::uint32_t setIndex) const {
    if (accumulation > 0) return builder_.build(frame, accumulation, setIndex);
    const auto step = stepAt(frame);
    LightingSet set = builder_.buildWith(frame, setIndex, step->sets.at(setIndex),
                                         step->pool->paths(pathsPerGroup_));
    // The pilots and the groups traced for this frame, if it traced any, in the statistics.
    if (firstFrame_ + step->index == frame) set.buildRays += step->pool->update().rays.share(sets_);
    return set;
}

}  // namespace igi
