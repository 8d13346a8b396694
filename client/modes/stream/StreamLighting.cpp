#include "modes/stream/StreamLighting.h"

#include <algorithm>
#include <stdexcept>

#include "math/Color.h"

namespace igi {

StreamLighting::StreamLighting(const LightingSetBuilder& builder, const TraceableScene& scene,
                               const SceneState& state, const RenderSettings& settings,
                               const LightingContext& context)
    : builder_(builder),
      scene_(scene),
      firstFrame_(context.firstFrame),
      setVpls_(std::size_t(std::max(1, settings.setCount()))) {
    if (!context.scene) throw std::invalid_argument("photon streaming needs the loaded scene");
    auto previous = std::dynamic_pointer_cast<const PhotonStream>(context.previous);
    auto sites = previous ? previous->sharedSites()
                          : std::make_shared<const std::vector<SurfaceLightSite>>(
                                // Placed in the scene as loaded: the same on every client,
                                // whenever it joined.
                                placeSurfaceLights(*context.scene, SceneState::of(*context.scene),
                                                   settings.streamVsls, settings.seed));
    lights_ = surfaceLightsIn(*context.scene, state, *sites);
    const auto shoot = [&](std::uint32_t index) {
        return shootPhotonBatch(builder_, lights_, settings.seed, index,
                                std::uint32_t(settings.streamPhotons), shootRays_);
    };
    if (previous)
        stream_ = previous->next(context.epoch, settings.streamWindow,
                                 std::make_shared<const PhotonBatch>(
                                     shoot(PhotonStream::batchIndex(context.firstFrame))));
    else
        stream_ = PhotonStream::first(sites, context.epoch, context.firstFrame,
                                      settings.streamWindow, shoot);

    // The VSLs as VPLs: one per lit side, at the VSL's place in this epoch.
    std::vector<glm::vec3> front, back;
    stream_->power(front, back);
    const float share = float(setVpls_.size());
    for (std::size_t i = 0; i < lights_.size(); ++i) {
        for (int side = 0; side < 2; ++side) {
            const glm::vec3 power = side == 0 ? front[i] : back[i];
            if (isBlack(power)) continue;
            const glm::vec3 n = side == 0 ? lights_[i].normal : -lights_[i].normal;
            Vpl v;
            v.position = scene_.offsetOrigin(lights_[i].position, n);
            v.normal = n;
            v.power = power * share;
            setVpls_[i % setVpls_.size()].push_back(v);
        }
    }
}

LightingSet StreamLighting::build(std::uint32_t frame, std::uint32_t accumulation,
                                  std::uint32_t setIndex) const {
    if (accumulation > 0) return builder_.build(frame, accumulation, setIndex);
    LightingSet set = builder_.buildWith(frame, setIndex, setVpls_.at(setIndex), stream_->paths());
    // The epoch's batch (the whole pool for a first epoch), in its first frame's statistics.
    if (frame == firstFrame_) set.buildRays += shootRays_.share(std::uint32_t(setVpls_.size()));
    return set;
}

}  // namespace igi
