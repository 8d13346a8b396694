#include "modes/cache/IrradianceCache.h"

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "math/Color.h"
#include "shading/ConnectionBound.h"

namespace igi {
namespace {

bool bit(const std::vector<std::uint64_t>& bits, std::size_t k) {
    return (bits[k >> 6] >> (k & 63)) & 1u;
}

void setBit(std::vector<std::uint64_t>& bits, std::size_t k) {
    bits[k >> 6] |= std::uint64_t(1) << (k & 63);
}

}  // namespace

struct IrradianceCache::Slot {
    std::once_flag once;
    std::shared_ptr<const Data> data;
    std::atomic<bool> ready{false};
};

IrradianceCache::IrradianceCache(const TraceableScene& scene,
                                 std::shared_ptr<const SceneState> state,
                                 std::shared_ptr<const CacheSites> sites,
                                 std::vector<LightingSetBuilder::NamedVpl> vpls,
                                 const Config& config,
                                 std::shared_ptr<const IrradianceCache> previous)
    : scene_(scene),
      diagonal_(scene.diagonal()),
      state_(std::move(state)),
      sites_(std::move(sites)),
      grid_(scene.geometry().scene(), *state_, *sites_, config.radius),
      vpls_(std::move(vpls)),
      config_(config),
      slots_(new Slot[2 * sites_->sites.size()]),
      counts_(std::make_shared<Counts>()) {
    // The previous cache's records can be brought up to date only if they are records of the
    // same sites, bound and interpolation, and kept their visibility.
    // The scene's scale too: it sets the offset of every shadow ray's origin, so a record's
    // visibility bits hold for the same scale only (a move may change the bounds).
    const bool usable = previous && previous->sites_ == sites_ &&
                        previous->diagonal_ == diagonal_ && previous->config_.keepVisibility &&
                        config_.keepVisibility &&
                        previous->config_.minDistance2 == config_.minDistance2 &&
                        previous->config_.radius == config_.radius;
    if (!usable) return;
    auto before = std::make_shared<Before>();
    const std::size_t records = 2 * sites_->sites.size();
    before->records.resize(records);
    for (std::uint32_t r = 0; r < records; ++r) before->records[r] = previous->computedRecord(r);
    std::unordered_map<std::uint64_t, std::int32_t> byName;
    for (std::size_t j = 0; j < previous->vpls_.size(); ++j)
        byName.emplace(previous->vpls_[j].id, std::int32_t(j));
    before->sameAs.assign(vpls_.size(), -1);
    for (std::size_t k = 0; k < vpls_.size(); ++k) {
        const auto it = byName.find(vpls_[k].id);
        if (it != byName.end() && previous->vpls_[std::size_t(it->second)].vpl == vpls_[k].vpl)
            before->sameAs[k] = it->second;
    }
    before->moved = std::make_unique<MovedInstances>(scene.geometry(), *previous->state_, *state_);
    before_ = std::move(before);
}

IrradianceCache::IrradianceCache(const TraceableScene& scene,
                                 std::shared_ptr<const SceneState> state,
                                 const IrradianceCache& same)
    : scene_(scene),
      diagonal_(scene.diagonal()),
      state_(std::move(state)),
      sites_(same.sites_),
      grid_(scene.geometry().scene(), *state_, *sites_, same.config_.radius),
      vpls_(same.vpls_),
      config_(same.config_),
      slots_(same.slots_),
      before_(same.before_),
      counts_(same.counts_) {}

IrradianceCache::~IrradianceCache() = default;

IrradianceCache::Link IrradianceCache::link(const Vpl& v, glm::vec3 origin, glm::vec3 n) const {
    Link out;
    const glm::vec3 toLight = v.position - origin;
    const float d2 = glm::dot(toLight, toLight);
    if (!(d2 > 0)) return out;
    const float d = std::sqrt(d2);
    const glm::vec3 w = toLight / d;
    const float cosX = glm::dot(n, w);
    if (cosX <= 0) return out;
    const float cosY = -glm::dot(v.normal, w);
    if (cosY <= 0) return out;
    // As EndPointShader connects a Lambertian point to a VPL, with the paper's bound.
    const auto [intensity, sharpnessY] = v.towards(w);
    const float kept =
        keptFraction(d2, config_.minDistance2, std::numeric_limits<float>::infinity(), 1.0f,
                     sharpnessY, BoundShape::Smooth);
    out.light = intensity * (cosX * cosY / d2 * kept);
    out.direction = w;
    out.tfar = d * (1.0f - kVplShadowShrink);
    return out;
}

std::shared_ptr<const IrradianceCache::Data> IrradianceCache::compute(std::uint32_t r,
                                                                      RayCounters& counters) const {
    auto data = std::make_shared<Data>();
    if (config_.keepVisibility) data->visible.assign((vpls_.size() + 63) / 64, 0);
    const std::uint32_t site = r / 2;
    const glm::vec3 n = (r & 1) ? -grid_.normal(site) : grid_.normal(site);
    const glm::vec3 origin = scene_.offsetOrigin(grid_.position(site), n);
    for (std::size_t k = 0; k < vpls_.size(); ++k) {
        const Link l = link(vpls_[k].vpl, origin, n);
        if (isBlack(l.light)) continue;
        if (scene_.occluded(origin, l.direction, l.tfar, counters)) continue;
        data->irradiance += l.light;
        if (config_.keepVisibility) setBit(data->visible, k);
    }
    counts_->traced.fetch_add(1, std::memory_order_relaxed);
    return data;
}

std::shared_ptr<const IrradianceCache::Data> IrradianceCache::update(std::uint32_t r,
                                                                     const Data& before,
                                                                     RayCounters& counters) const {
    const std::uint32_t site = r / 2;
    const std::vector<std::int32_t>& sameAs = before_->sameAs;
    const MovedInstances& moved = *before_->moved;
    if (moved.meshMoved(sites_->sites[site].mesh)) return compute(r, counters);  // case 5
    auto data = std::make_shared<Data>();
    data->visible.assign((vpls_.size() + 63) / 64, 0);
    const glm::vec3 n = (r & 1) ? -grid_.normal(site) : grid_.normal(site);
    const glm::vec3 origin = scene_.offsetOrigin(grid_.position(site), n);
    for (std::size_t k = 0; k < vpls_.size(); ++k) {
        const Link l = link(vpls_[k].vpl, origin, n);
        if (isBlack(l.light)) continue;
        const std::int32_t j = sameAs[k];
        bool visible;
        if (j < 0) {  // cases 1 and 2: a new or changed VPL
            visible = !scene_.occluded(origin, l.direction, l.tfar, counters);
        } else if (moved.occluded(false, origin, l.direction, l.tfar, counters)) {
            visible = false;  // case 3: a moved object is in the way now
        } else if (bit(before.visible, std::size_t(j))) {
            visible = true;
        } else if (!moved.occluded(true, origin, l.direction, l.tfar, counters)) {
            visible = false;  // hidden by something that did not move
        } else {              // case 4: hidden by a moved object before; perhaps by nothing now
            visible = !scene_.occluded(origin, l.direction, l.tfar, counters);
        }
        if (!visible) continue;
        data->irradiance += l.light;
        setBit(data->visible, k);
    }
    counts_->updated.fetch_add(1, std::memory_order_relaxed);
    return data;
}

glm::vec3 IrradianceCache::record(std::uint32_t r, RayCounters& counters) const {
    Slot& slot = slots_[r];
    std::call_once(slot.once, [&] {
        const Data* before =
            before_ && r < before_->records.size() ? before_->records[r].get() : nullptr;
        slot.data = before ? update(r, *before, counters) : compute(r, counters);
        slot.ready.store(true, std::memory_order_release);
    });
    return slot.data->irradiance;
}

std::shared_ptr<const IrradianceCache::Data> IrradianceCache::computedRecord(
    std::uint32_t r) const {
    const Slot& slot = slots_[r];
    return slot.ready.load(std::memory_order_acquire) ? slot.data : nullptr;
}

glm::vec3 IrradianceCache::irradianceAt(glm::vec3 position, glm::vec3 n,
                                        RayCounters& counters) const {
    const glm::vec3 origin = scene_.offsetOrigin(position, n);
    glm::vec3 e(0.0f);
    for (const LightingSetBuilder::NamedVpl& v : vpls_) {
        const Link l = link(v.vpl, origin, n);
        if (isBlack(l.light)) continue;
        if (!scene_.occluded(origin, l.direction, l.tfar, counters)) e += l.light;
    }
    return e;
}

glm::vec3 IrradianceCache::irradiance(glm::vec3 position, glm::vec3 faceNormal,
                                      RayCounters& counters) const {
    return interpolate(
        grid_, position, faceNormal, config_.maxAngleCos,
        [&](std::uint32_t r) { return record(r, counters); },
        [&] { return irradianceAt(position, faceNormal, counters); });
}

}  // namespace igi
