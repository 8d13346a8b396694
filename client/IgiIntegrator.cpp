#include "IgiIntegrator.h"

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "math/Color.h"
#include "math/Warp.h"

namespace igi {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

}  // namespace

glm::vec3 emittedToward(const SurfacePoint& hit, glm::vec3 wo) {
    if (!hit.material->isEmissive() || glm::dot(wo, hit.geometricNormal) <= 0)
        return glm::vec3(0.0f);
    return hit.material->emission;
}

IgiIntegrator::IgiIntegrator(const TraceableScene& scene, const Lights& lights,
                             const RenderSettings& settings, const CameraModel& camera)
    : scene_(scene), settings_(settings), camera_(camera), shader_(scene, lights, settings) {}

PixelResult IgiIntegrator::shade(int x, int y, std::uint32_t pixelIndex, std::uint32_t frame,
                                 const LightingSet& set, RayCounters& counters) const {
    PixelResult result;
    const PixelSampler sampler(settings_.seed, SampleStream::EyePath, pixelIndex, frame);
    PathRandom random(sampler, 2);  // 0 and 1: the position in the pixel
    const glm::vec3 direction =
        camera_.direction(float(x) + sampler.get(0), float(y) + sampler.get(1));
    SurfacePoint hit;
    if (!scene_.intersect(camera_.origin(), direction, kInfinity, hit, counters)) return result;

    const glm::vec3 wo = -direction;
    result.unfiltered += emittedToward(hit, wo);
    const Lobes lobes = lobesAt(hit, wo);

    // Split once: the non-delta part here, and one path per delta component.
    std::optional<ChainEnd> ends[3];
    if (lobes.hasNonDelta()) ends[0] = ChainEnd{hit, lobes, glm::vec3(1.0f), hit.distance};
    const Lobe deltas[2] = {Lobe::Reflection, Lobe::Transmission};
    for (int i = 0; i < 2; ++i) {
        glm::vec3 next, weight;
        if (lobeWeight(lobes, deltas[i]) <= 0 ||
            !sampleLobe(lobes, deltas[i], {0.5f, 0.5f}, next, weight))
            continue;
        ends[i + 1] = followDeltaChain(
            scene_, scene_.offsetOrigin(hit.position, lobes.faceNormal, next), next, weight,
            hit.distance, settings_.maxEyeDepth, [&] { return random.next(); }, result.unfiltered,
            counters);
    }

    // The end point that reflects most is the one the master filters.
    int primary = -1;
    auto reflectance = [](const ChainEnd& e) {
        return luminance(e.throughput * (e.lobes.brdf.kd + e.lobes.brdf.ks));
    };
    for (int i = 0; i < 3; ++i)
        if (ends[i] && (primary < 0 || reflectance(*ends[i]) > reflectance(*ends[primary])))
            primary = i;
    if (primary < 0) return result;
    for (int i = 0; i < 3; ++i) {
        if (!ends[i]) continue;
        const ChainEnd& e = *ends[i];
        const EndPointLight light =
            shader_.shade(ShadingPoint::at(e.hit, e.lobes), set, random, counters);
        if (i == primary) {
            result.irradiance = light.irradiance;
            result.reflectance = e.throughput * e.lobes.brdf.kd;
            result.glossy = e.throughput * light.glossy;
            result.normal = e.lobes.normal;
            result.depth = e.pathLength;
            result.firstHit = i == 0;
        } else {
            result.unfiltered += e.throughput * light.radiance(e.lobes.brdf);
        }
    }
    return result;
}

glm::vec3 IgiIntegrator::irradianceOverPi(glm::vec3 position, glm::vec3 normal,
                                          glm::vec3 faceNormal, const LightingSet& set,
                                          RayCounters& counters) const {
    ShadingPoint p;
    p.position = position;
    p.faceNormal = faceNormal;
    p.brdf = SurfaceBrdf::make(glm::vec3(1.0f), glm::vec3(0.0f), 0.0f, normal);
    p.wo = normal;
    p.mirror = normal;
    return shader_.shadeWithoutContinuation(p, set, counters).irradiance;
}

}  // namespace igi
