#include "modes/cache/CacheLighting.h"

#include <algorithm>
#include <stdexcept>

namespace igi {
namespace {

// Frames whose records are kept for tiles still in flight.
constexpr std::uint32_t kKeptFrames = 8;

bool sameConfig(const IrradianceCache::Config& a, const IrradianceCache::Config& b) {
    return a.radius == b.radius && a.maxAngleCos == b.maxAngleCos &&
           a.minDistance2 == b.minDistance2 && a.keepVisibility == b.keepVisibility;
}

// Every set's VPLs of one walk, each with 1 / K of its set's power: one collection.
void addShare(std::vector<LightingSetBuilder::NamedVpl>& collection,
              const std::vector<LightingSetBuilder::NamedVpl>& set, float share) {
    for (LightingSetBuilder::NamedVpl v : set) {
        v.vpl.power *= share;
        v.vpl.glossyPower *= share;
        collection.push_back(v);
    }
}

}  // namespace

CacheLighting::CacheLighting(const LightingSetBuilder& builder, const TraceableScene& scene,
                             const SceneState& state, const RenderSettings& settings,
                             const LightingContext& context)
    : builder_(builder),
      scene_(scene),
      state_(std::make_shared<const SceneState>(state)),
      sets_(std::uint32_t(std::max(1, settings.setCount()))) {
    auto previous = std::dynamic_pointer_cast<const IrradianceCache>(context.previous);
    if (context.previous && !previous)
        throw std::invalid_argument("instant caching continues another method's state");
    sites_ = previous ? previous->sites()
                      : std::make_shared<const CacheSites>(
                            CacheSites::forScene(scene.geometry().scene(), settings));
    // As LightingSetBuilder computes the first frame's bound.
    const float minDistance = settings.clampDistance * scene.diagonal();
    config_.radius = std::max(sites_->spacing, 1e-30f) * settings.cacheRadius;
    config_.maxAngleCos = kInterpolationMaxAngleCos;
    config_.minDistance2 = minDistance * minDistance;
    config_.keepVisibility = true;

    std::vector<LightingSetBuilder::NamedVpl> collection;
    stableSets_.resize(sets_);
    for (std::uint32_t k = 0; k < sets_; ++k) {
        const auto named =
            builder.namedVpls(SampleStream::StableVplPaths, 0, false, k, stableRays_);
        for (const auto& v : named) stableSets_[k].push_back(v.vpl);
        addShare(collection, named, 1.0f / float(sets_));
    }
    stablePaths_ = builder.vplPaths();
    if (previous && previous->state()->sameLighting(state) &&
        sameConfig(previous->config(), config_))
        stable_ = std::make_shared<const IrradianceCache>(scene, state_, *previous);
    else
        stable_ = std::make_shared<const IrradianceCache>(
            scene, state_, sites_, std::move(collection), config_, std::move(previous));
}

std::shared_ptr<const IrradianceCache> CacheLighting::frameCache(std::uint32_t frame,
                                                                 std::uint32_t accumulation,
                                                                 float minDistance2) const {
    std::lock_guard lock(mutex_);
    auto it = frames_.find(frame);
    if (it != frames_.end()) return it->second;
    // The frame's own light paths, as IGI's sets of this frame walk them.
    const bool roulette = builder_.settings().roulette && accumulation > 0;
    std::vector<LightingSetBuilder::NamedVpl> collection;
    RayCounters rays;
    for (std::uint32_t k = 0; k < sets_; ++k)
        addShare(collection, builder_.namedVpls(SampleStream::VplPaths, frame, roulette, k, rays),
                 1.0f / float(sets_));
    IrradianceCache::Config config = config_;
    config.minDistance2 = minDistance2;
    config.keepVisibility = false;
    auto cache = std::make_shared<const IrradianceCache>(scene_, state_, sites_,
                                                         std::move(collection), config);
    frames_.erase(frames_.begin(),
                  frames_.lower_bound(frame > kKeptFrames ? frame - kKeptFrames : 0));
    frames_.emplace(frame, cache);
    return cache;
}

LightingSet CacheLighting::build(std::uint32_t frame, std::uint32_t accumulation,
                                 std::uint32_t setIndex) const {
    LightingSet set;
    if (accumulation == 0) {
        set = builder_.buildWith(frame, setIndex, stableSets_.at(setIndex), stablePaths_);
        set.indirectIrradiance = stable_;
    } else {
        set = builder_.build(frame, accumulation, setIndex);
        set.indirectIrradiance = frameCache(frame, accumulation, set.minDistance2);
    }
    set.boundShape = BoundShape::Smooth;
    return set;
}

}  // namespace igi
