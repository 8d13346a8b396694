#include "IgiIntegrator.h"

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "math/Color.h"
#include "math/Warp.h"

namespace igi {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();
// Shadow rays stop this fraction short of a VPL, which sits on a surface of its own.
constexpr float kShadowShrink = 1e-4f;
// Eye sampler dimensions: 2 for the pixel position, then kDimsPerBounce per specular bounce.
constexpr std::uint32_t kDimsPerBounce = 3;

}  // namespace

glm::vec3 emittedToward(const SurfacePoint& hit, glm::vec3 wo) {
    if (!hit.material->isEmissive() || glm::dot(wo, hit.geometricNormal) <= 0)
        return glm::vec3(0.0f);
    return hit.material->emission;
}

IgiIntegrator::IgiIntegrator(const TraceableScene& scene, const RenderSettings& settings,
                             const CameraModel& camera)
    : scene_(scene), settings_(settings), camera_(camera) {
    const float d = settings.clampDistance * scene.diagonal();
    clampDistance2_ = d * d;
}

PixelResult IgiIntegrator::shade(int x, int y, std::uint32_t pixelIndex, std::uint32_t frame,
                                 const LightingSet& set, RayCounters& counters) const {
    PixelResult result;
    const PixelSampler sampler(settings_.seed, SampleStream::EyePath, pixelIndex, frame);
    const glm::vec3 direction =
        camera_.direction(float(x) + sampler.get(0), float(y) + sampler.get(1));
    SurfacePoint hit;
    if (!scene_.intersect(camera_.origin(), direction, kInfinity, hit, counters)) return result;

    const glm::vec3 wo = -direction;
    result.unfiltered += emittedToward(hit, wo);
    const Lobes lobes = lobesAt(hit, wo);

    // Split once: the diffuse part here, and one path per specular component.
    std::optional<EndPoint> ends[3];
    if (lobes.hasDiffuse())
        ends[0] =
            EndPoint{hit.position, lobes.normal, lobes.faceNormal, lobes.diffuse, hit.distance};
    const std::uint32_t dimsPerContinuation =
        kDimsPerBounce * std::uint32_t(settings_.maxEyeDepth + 1);
    if (!isBlack(lobes.reflection))
        ends[1] =
            followSpecular(hit, lobes, Lobe::Reflection, sampler, 2, result.unfiltered, counters);
    if (!isBlack(lobes.transmission))
        ends[2] = followSpecular(hit, lobes, Lobe::Transmission, sampler, 2 + dimsPerContinuation,
                                 result.unfiltered, counters);

    int primary = -1;
    for (int i = 0; i < 3; ++i)
        if (ends[i] && (primary < 0 ||
                        luminance(ends[i]->reflectance) > luminance(ends[primary]->reflectance)))
            primary = i;
    if (primary < 0) return result;
    for (int i = 0; i < 3; ++i) {
        if (!ends[i]) continue;
        const EndPoint& e = *ends[i];
        const glm::vec3 e_pi = irradianceOverPi(e.position, e.normal, e.faceNormal, set, counters);
        if (i == primary) {
            result.irradiance = e_pi;
            result.reflectance = e.reflectance;
            result.normal = e.normal;
            result.depth = e.depth;
        } else {
            result.unfiltered += e.reflectance * e_pi;
        }
    }
    return result;
}

std::optional<IgiIntegrator::EndPoint> IgiIntegrator::followSpecular(
    const SurfacePoint& first, const Lobes& firstLobes, Lobe lobe, const PixelSampler& sampler,
    std::uint32_t firstDim, glm::vec3& unfiltered, RayCounters& counters) const {
    glm::vec3 direction, throughput;
    if (!sampleSpecular(firstLobes, lobe, {sampler.get(firstDim), sampler.get(firstDim + 1)},
                        direction, throughput))
        return std::nullopt;
    glm::vec3 origin = scene_.offsetOrigin(first.position, firstLobes.faceNormal, direction);
    float pathLength = first.distance;
    SurfacePoint hit;
    for (int bounce = 1; bounce <= settings_.maxEyeDepth; ++bounce) {
        if (!scene_.intersect(origin, direction, kInfinity, hit, counters)) return std::nullopt;
        pathLength += hit.distance;
        const glm::vec3 wo = -direction;
        unfiltered += throughput * emittedToward(hit, wo);  // lights seen in mirrors and glass
        const Lobes lobes = lobesAt(hit, wo);
        const std::uint32_t dim = firstDim + kDimsPerBounce * std::uint32_t(bounce);
        Lobe next;
        float probability = 0;
        if (!chooseLobe(lobes, sampler.get(dim), next, probability)) return std::nullopt;
        if (next == Lobe::Diffuse)
            return EndPoint{hit.position, lobes.normal, lobes.faceNormal,
                            throughput * lobes.diffuse / probability, pathLength};
        if (bounce == settings_.maxEyeDepth) return std::nullopt;
        glm::vec3 weight;
        if (!sampleSpecular(lobes, next, {sampler.get(dim + 1), sampler.get(dim + 2)}, direction,
                            weight))
            return std::nullopt;
        throughput *= weight / probability;
        origin = scene_.offsetOrigin(hit.position, lobes.faceNormal, direction);
    }
    return std::nullopt;
}

glm::vec3 IgiIntegrator::irradianceOverPi(glm::vec3 position, glm::vec3 normal,
                                          glm::vec3 faceNormal, const LightingSet& set,
                                          RayCounters& counters) const {
    const glm::vec3 origin = scene_.offsetOrigin(position, faceNormal);
    glm::vec3 irradiance(0.0f);
    // Shadow rays go out in packets of up to 8 (they share the origin); contributions are
    // added in the VPLs' order, so the sum is the same as one ray at a time.
    constexpr int kPacket = TraceableScene::kPacket;
    glm::vec3 directions[kPacket], contributions[kPacket];
    float tfar[kPacket];
    bool blocked[kPacket];
    int pending = 0;
    auto flush = [&] {
        if (pending == 0) return;
        if (pending == 1)
            blocked[0] = scene_.occluded(origin, directions[0], tfar[0], counters);
        else
            scene_.occluded8(origin, directions, tfar, pending, blocked, counters);
        for (int i = 0; i < pending; ++i)
            if (!blocked[i]) irradiance += contributions[i];
        pending = 0;
    };
    auto gather = [&](const Vpl& v, float minDistance2) {
        const glm::vec3 toLight = v.position - origin;
        const float distance2 = glm::dot(toLight, toLight);
        if (!(distance2 > 0)) return;
        const float distance = std::sqrt(distance2);
        const glm::vec3 w = toLight / distance;
        const float cosX = glm::dot(normal, w);
        if (cosX <= 0 || glm::dot(faceNormal, w) <= 0) return;
        const float cosY = v.omni ? 1.0f : -glm::dot(v.normal, w);
        if (cosY <= 0) return;
        // The clamp bounds the 1/d^2 spike near creases; minDistance is a fraction of the
        // scene's size, so it means the same at every scale.
        const float g = cosX * cosY / std::max(distance2, minDistance2);
        directions[pending] = w;
        tfar[pending] = distance * (1.0f - kShadowShrink);
        contributions[pending] = v.power * g;
        if (++pending == kPacket) flush();
    };
    for (const Vpl& v : set.direct) gather(v, 0.0f);
    for (const Vpl& v : set.indirect) gather(v, clampDistance2_);
    flush();

    const float r = set.caustics.radius();
    if (!set.caustics.photons().empty()) {
        glm::vec3 flux(0.0f);
        set.caustics.forEachNear(position, [&](const CausticPhoton& p) {
            if (glm::dot(p.direction, normal) < 0) flux += p.power;  // arrived on this side
        });
        irradiance += flux / (kPi * r * r);
    }
    return irradiance * kInvPi;
}

}  // namespace igi
