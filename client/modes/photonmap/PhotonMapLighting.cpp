#include "modes/photonmap/PhotonMapLighting.h"

#include <algorithm>
#include <stdexcept>

namespace igi {
namespace {

// Frames whose screen caustics and emission steps are kept for tiles still in flight (the
// master has at most a few frames open at once).
constexpr std::uint32_t kKeptFrames = 8;

}  // namespace

PhotonMapLighting::PhotonMapLighting(const LightingSetBuilder& builder, const TraceableScene& scene,
                                     const SceneState& state, const RenderSettings& settings,
                                     const ImageSettings& image, const LightingContext& context)
    : builder_(builder),
      scene_(scene),
      state_(std::make_shared<const SceneState>(state)),
      image_(image),
      tracer_(builder, state_, settings),
      firstFrame_(context.firstFrame),
      sets_(std::uint32_t(std::max(1, settings.setCount()))),
      screen_(settings.photonmapScreenCaustics),
      neighbours_(std::max(1, settings.photonmapNeighbours)) {
    auto previous = std::dynamic_pointer_cast<const PhotonMapHistory>(context.previous);
    if (context.previous && !previous)
        throw std::invalid_argument("simulated photon mapping continues another method's state");
    sites_ = previous && previous->cache ? previous->cache->sites()
                                         : std::make_shared<const CacheSites>(CacheSites::forScene(
                                               scene.geometry().scene(), settings));
    config_.radius = std::max(sites_->spacing, 1e-30f) * settings.cacheRadius;
    config_.maxAngleCos = kInterpolationMaxAngleCos;
    config_.gatherRays = settings.photonmapGather;
    config_.maxEyeDepth = settings.maxEyeDepth;
    config_.seed = settings.seed;

    auto step = std::make_shared<Step>();
    if (previous) {
        step->emission = previous->emission->step(tracer_, firstFrame_);
        step->cache = reconstruct(step->emission, previous->cache, previous->emission->version());
    } else {
        step->emission = PhotonEmission::traceAll(tracer_, firstFrame_);
        step->cache = reconstruct(step->emission, nullptr, 0);
    }
    steps_.push_back(std::move(step));
}

std::shared_ptr<const PhotonMapCache> PhotonMapLighting::reconstruct(
    const std::shared_ptr<const PhotonEmission>& emission,
    const std::shared_ptr<const PhotonMapCache>& reuse, std::uint64_t reuseVersion) const {
    if (reuse && reuseVersion == emission->version() && reuse->state()->sameLighting(*state_)) {
        if (reuse->state() == state_) return reuse;
        return std::make_shared<const PhotonMapCache>(scene_, state_, *reuse);
    }
    auto map = std::make_shared<const PhotonMap>(emission->hits(), sites_->area, neighbours_);
    return std::make_shared<const PhotonMapCache>(scene_, state_, sites_, std::move(map), config_);
}

std::shared_ptr<const PhotonMapLighting::Step> PhotonMapLighting::stepAt(
    std::uint32_t frame) const {
    const std::size_t j = frame > firstFrame_ ? frame - firstFrame_ : 0;
    std::lock_guard lock(mutex_);
    // Each frame's emission from the one before, in frame order, until no photon can diverge:
    // the emission of a frame does not depend on which frames this client rendered.
    while (stepsBase_ + steps_.size() <= j) {
        const std::size_t index = stepsBase_ + steps_.size();
        const auto next = std::uint32_t(firstFrame_ + index);
        const Step& last = *steps_.back();
        if (last.emission->settled(*state_, next, tracer_.photons())) break;
        auto step = std::make_shared<Step>();
        step->index = index;
        step->emission = last.emission->step(tracer_, next);
        step->cache = reconstruct(step->emission, last.cache, last.emission->version());
        steps_.push_back(std::move(step));
        if (steps_.size() > kKeptFrames) steps_.pop_front(), ++stepsBase_;
    }
    if (j < stepsBase_) return steps_.front();
    return steps_[std::min(j - stepsBase_, steps_.size() - 1)];
}

std::shared_ptr<const PhotonEmission> PhotonMapLighting::emissionAt(std::uint32_t frame) const {
    return stepAt(frame)->emission;
}

std::shared_ptr<const PhotonMapCache> PhotonMapLighting::cacheAt(std::uint32_t frame) const {
    return stepAt(frame)->cache;
}

std::shared_ptr<const LightingHistory> PhotonMapLighting::history(
    std::uint32_t nextFirstFrame) const {
    const auto step = stepAt(nextFirstFrame > firstFrame_ ? nextFirstFrame - 1 : firstFrame_);
    auto h = std::make_shared<PhotonMapHistory>();
    h->emission = step->emission;
    h->cache = step->cache;
    return h;
}

std::shared_ptr<const ScreenCaustics> PhotonMapLighting::screenCaustics(std::uint32_t frame) const {
    {
        std::lock_guard lock(mutex_);
        auto it = screens_.find(frame);
        if (it != screens_.end()) return it->second;
    }
    std::uint32_t shot = 0;
    RayCounters rays;
    auto photons = builder_.pooledCaustics(frame, shot, rays);
    auto made = std::make_shared<const ScreenCaustics>(scene_, state_->camera, image_.width,
                                                       image_.height, *photons);
    std::lock_guard lock(mutex_);
    auto [it, inserted] = screens_.emplace(frame, made);
    screens_.erase(screens_.begin(),
                   screens_.lower_bound(frame > kKeptFrames ? frame - kKeptFrames : 0));
    return it->second;
}

LightingSet PhotonMapLighting::build(std::uint32_t frame, std::uint32_t accumulation,
                                     std::uint32_t setIndex) const {
    if (accumulation > 0) return builder_.build(frame, accumulation, setIndex);
    const auto step = stepAt(frame);
    LightingSet set = builder_.buildDirect(frame, setIndex, !screen_);
    set.indirectIrradiance = step->cache;
    if (screen_) set.screenCaustics = screenCaustics(frame);
    // The photons checked and traced for this frame, if it traced any, in the statistics.
    if (firstFrame_ + step->index == frame)
        set.buildRays += step->emission->update().rays.share(sets_);
    return set;
}

}  // namespace igi
