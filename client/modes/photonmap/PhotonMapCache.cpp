#include "modes/photonmap/PhotonMapCache.h"

#include <cstring>

#include <glm/geometric.hpp>

#include "math/Frame.h"
#include "math/Warp.h"
#include "sampling/Hash.h"
#include "sampling/Sobol.h"
#include "shading/DeltaChain.h"

namespace igi {
namespace {

constexpr std::uint64_t kGatherStream = 0x474154u;  // "GAT"

struct Slot {
    std::once_flag once;
    glm::vec3 value{0.0f};
};

// A key for a point that has no site: its position's bits.
std::uint64_t pointKey(glm::vec3 p) {
    std::uint32_t b[3];
    std::memcpy(b, &p, sizeof b);
    return hashValues(b[0], b[1], b[2]) | (std::uint64_t(1) << 63);
}

}  // namespace

struct PhotonMapCache::Slots {
    explicit Slots(std::size_t records)
        : approximated(new Slot[records]), indirect(new Slot[records]) {}
    std::unique_ptr<Slot[]> approximated, indirect;
};

PhotonMapCache::PhotonMapCache(const TraceableScene& scene, std::shared_ptr<const SceneState> state,
                               std::shared_ptr<const CacheSites> sites,
                               std::shared_ptr<const PhotonMap> map, const Config& config)
    : scene_(scene),
      state_(std::move(state)),
      sites_(std::move(sites)),
      grid_(scene.geometry().scene(), *state_, *sites_, config.radius),
      map_(std::move(map)),
      config_(config),
      slots_(std::make_shared<Slots>(2 * sites_->sites.size())),
      counts_(std::make_shared<Counts>()) {}

PhotonMapCache::PhotonMapCache(const TraceableScene& scene, std::shared_ptr<const SceneState> state,
                               const PhotonMapCache& same)
    : scene_(scene),
      state_(std::move(state)),
      sites_(same.sites_),
      grid_(scene.geometry().scene(), *state_, *sites_, same.config_.radius),
      map_(same.map_),
      config_(same.config_),
      slots_(same.slots_),
      counts_(same.counts_) {}

PhotonMapCache::~PhotonMapCache() = default;

glm::vec3 PhotonMapCache::approximated(std::uint32_t r) const {
    Slot& slot = slots_->approximated[r];
    std::call_once(slot.once, [&] {
        const std::uint32_t site = r / 2;
        const glm::vec3 n = (r & 1) ? -grid_.normal(site) : grid_.normal(site);
        slot.value = map_->radiance(grid_.position(site), n);
    });
    return slot.value;
}

glm::vec3 PhotonMapCache::indirect(std::uint32_t r, RayCounters& counters) const {
    Slot& slot = slots_->indirect[r];
    std::call_once(slot.once, [&] {
        const std::uint32_t site = r / 2;
        const glm::vec3 n = (r & 1) ? -grid_.normal(site) : grid_.normal(site);
        slot.value = gather(grid_.position(site), n, r, counters);
    });
    return slot.value;
}

glm::vec3 PhotonMapCache::gather(glm::vec3 position, glm::vec3 n, std::uint64_t key,
                                 RayCounters& counters) const {
    counts_->gathers.fetch_add(1, std::memory_order_relaxed);
    const std::uint64_t h = hashValues(config_.seed, kGatherStream, key);
    const auto s0 = std::uint32_t(h), s1 = std::uint32_t(h >> 32);
    const Frame frame(n);
    const glm::vec3 origin = scene_.offsetOrigin(position, n);
    const int rays = std::max(1, config_.gatherRays);
    glm::vec3 sum(0.0f);
    for (int i = 0; i < rays; ++i) {
        const glm::vec2 u(Sobol::scrambled(std::uint32_t(i), 0, s0),
                          Sobol::scrambled(std::uint32_t(i), 1, s1));
        const glm::vec3 w = frame.toWorld(squareToCosineHemisphere(u));
        SplitMix64 random(hashValues(h, std::uint32_t(i)));
        glm::vec3 emitted(0.0f);  // lights seen directly are the pixels' light samples' part
        const auto end = followDeltaChain(
            scene_, origin, w, glm::vec3(1.0f), 0.0f, std::max(1, config_.maxEyeDepth),
            [&] { return random.uniform(); }, emitted, counters);
        if (!end) continue;
        sum +=
            end->throughput * surfaceRadiance(end->hit.position, end->lobes.faceNormal, counters);
    }
    // E = integral of L cos over the hemisphere; with cosine-distributed directions
    // (pdf cos / pi) each ray's L counts pi / rays.
    return sum * (kPi / float(rays));
}

glm::vec3 PhotonMapCache::surfaceRadiance(glm::vec3 position, glm::vec3 faceNormal,
                                          RayCounters&) const {
    return interpolate(
        grid_, position, faceNormal, config_.maxAngleCos,
        [&](std::uint32_t r) { return approximated(r); },
        [&] { return map_->radiance(position, faceNormal); });
}

glm::vec3 PhotonMapCache::irradiance(glm::vec3 position, glm::vec3 faceNormal,
                                     RayCounters& counters) const {
    return interpolate(
        grid_, position, faceNormal, config_.maxAngleCos,
        [&](std::uint32_t r) { return indirect(r, counters); },
        [&] { return gather(position, faceNormal, pointKey(position), counters); });
}

}  // namespace igi
