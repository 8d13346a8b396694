#pragma once

#include <limits>
#include <optional>
#include <utility>

#include <glm/vec3.hpp>

#include "math/Color.h"
#include "shading/Scattering.h"
#include "tracing/TraceableScene.h"

namespace igi {

/// Radiance an emitter sends toward wo from a hit (zero on its back side or if it is no emitter).
glm::vec3 emittedToward(const SurfacePoint& hit, glm::vec3 wo);

/// Where a chain of mirror and glass bounces ended: a non-delta surface point, the throughput
/// of the chain up to it (the choice of its non-delta part included), and the chain's length.
struct ChainEnd {
    SurfacePoint hit;
    Lobes lobes;
    glm::vec3 throughput{0.0f};
    float pathLength = 0;

    ChainEnd() = default;
    /// At `hit` seen from wo, its lobes built in place. (Eye paths build one per pixel in
    /// PixelPath::ends: neither a temporary copied there nor a whole ChainEnd cleared first,
    /// 288 bytes that GCC clears and copies through libc's memset and memcpy.)
    ChainEnd(const SurfacePoint& hit, glm::vec3 wo, glm::vec3 throughput, float pathLength)
        : hit(hit), lobes(lobesAt(hit, wo)), throughput(throughput), pathLength(pathLength) {}
};

/// The probability with which chooseLobe (without roulette) takes one of the non-delta lobes.
inline float nonDeltaProbability(const Lobes& l) {
    const float nonDelta = lobeWeight(l, Lobe::Diffuse) + lobeWeight(l, Lobe::Glossy);
    const float total =
        nonDelta + lobeWeight(l, Lobe::Reflection) + lobeWeight(l, Lobe::Transmission);
    return total > 0 ? nonDelta / total : 0.0f;
}

/// Follows a path through mirrors and glass from `firstHit`, where a ray along `direction` has
/// already landed: at every vertex one lobe is chosen (one number from `next()`), and the path
/// ends at the first vertex whose non-delta part is chosen, written into `out`. Emitters met
/// on the way add throughput * Le to `emitted`, and so does the sky where the path leaves the
/// scene. `out` is left empty when the path leaves the scene, is absorbed, or has
/// not ended after `maxHits` intersections (the first hit counts as one).
/// `atRoughGlass(hit, lobes, throughput)` is called at every vertex where the path goes on
/// through rough glass, with the throughput up to it (its lobe's choice included), before the
/// path leaves it: IGI adds the light that only a light sample finds there.
/// The end is built where the caller keeps it (eye paths: PixelPath::ends), not returned and
/// copied: a ChainEnd is 288 bytes, copied once per eye path.
template <typename Next, typename AtRoughGlass>
void followDeltaChainInto(std::optional<ChainEnd>& out, const TraceableScene& scene,
                          const SurfacePoint& firstHit, glm::vec3 direction, glm::vec3 throughput,
                          float pathLength, int maxHits, Next&& next, glm::vec3& emitted,
                          RayCounters& counters, AtRoughGlass&& atRoughGlass) {
    constexpr float kInfinity = std::numeric_limits<float>::infinity();
    // (The throughput and the length are set where the chain ends.)
    ChainEnd& end = out.emplace(firstHit, -direction, glm::vec3(0.0f), 0.0f);
    for (int hits = 1;; ++hits) {
        pathLength += end.hit.distance;
        const glm::vec3 wo = -direction;
        emitted += throughput * emittedToward(end.hit, wo);
        if (hits > 1) setLobesAt(end.hit, wo, end.lobes);
        Lobe lobe;
        float probability = 0;
        const float uLobe = next();
        if (!chooseLobe(end.lobes, uLobe, lobe, probability)) break;
        if (!isDelta(lobe)) {
            end.throughput = throughput / nonDeltaProbability(end.lobes);
            end.pathLength = pathLength;
            return;
        }
        if (hits >= maxHits) break;
        glm::vec3 weight;
        const float u0 = next(), u1 = next();
        if (lobe == Lobe::Transmission && end.lobes.roughGlass())
            atRoughGlass(end.hit, end.lobes, throughput / probability);
        // Rough glass chooses between reflection and refraction with the lobe's number again.
        if (!sampleLobe(end.lobes, lobe, {u0, u1}, remapChoice(uLobe, probability), direction,
                        weight))
            break;
        // Eye paths carry radiance (radianceScale: refraction's eta^2).
        throughput *= weight * (radianceScale(end.lobes, direction) / probability);
        if (isBlack(throughput)) break;
        const glm::vec3 origin =
            scene.offsetOrigin(end.hit.position, end.lobes.faceNormal, direction);
        if (!scene.intersect(origin, direction, kInfinity, end.hit, counters)) {
            emitted += throughput * scene.skyRadiance(direction);  // seen through the mirrors
            break;
        }
    }
    out.reset();
}

/// followDeltaChainInto, the end returned.
template <typename Next, typename AtRoughGlass>
std::optional<ChainEnd> followDeltaChainFrom(const TraceableScene& scene,
                                             const SurfacePoint& firstHit, glm::vec3 direction,
                                             glm::vec3 throughput, float pathLength, int maxHits,
                                             Next&& next, glm::vec3& emitted, RayCounters& counters,
                                             AtRoughGlass&& atRoughGlass) {
    std::optional<ChainEnd> end;
    followDeltaChainInto(end, scene, firstHit, direction, throughput, pathLength, maxHits,
                         std::forward<Next>(next), emitted, counters,
                         std::forward<AtRoughGlass>(atRoughGlass));
    return end;
}

/// followDeltaChainFrom with nothing added at rough glass.
template <typename Next>
std::optional<ChainEnd> followDeltaChainFrom(const TraceableScene& scene,
                                             const SurfacePoint& firstHit, glm::vec3 direction,
                                             glm::vec3 throughput, float pathLength, int maxHits,
                                             Next&& next, glm::vec3& emitted,
                                             RayCounters& counters) {
    return followDeltaChainFrom(scene, firstHit, direction, throughput, pathLength, maxHits,
                                std::forward<Next>(next), emitted, counters,
                                [](const SurfacePoint&, const Lobes&, glm::vec3) {});
}

/// followDeltaChainFrom where the ray from `origin` along `direction` lands (nothing if it
/// leaves the scene, or if maxHits < 1).
template <typename Next>
std::optional<ChainEnd> followDeltaChain(const TraceableScene& scene, glm::vec3 origin,
                                         glm::vec3 direction, glm::vec3 throughput,
                                         float pathLength, int maxHits, Next&& next,
                                         glm::vec3& emitted, RayCounters& counters) {
    SurfacePoint first;
    if (maxHits < 1) return std::nullopt;
    if (!scene.intersect(origin, direction, std::numeric_limits<float>::infinity(), first,
                         counters)) {
        emitted += throughput * scene.skyRadiance(direction);
        return std::nullopt;
    }
    return followDeltaChainFrom(scene, first, direction, throughput, pathLength, maxHits,
                                std::forward<Next>(next), emitted, counters);
}

}  // namespace igi
