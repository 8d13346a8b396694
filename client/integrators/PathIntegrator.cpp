#include "integrators/PathIntegrator.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "integrators/PixelSampler.h"
#include "integrators/RoughGlassLight.h"
#include "math/Color.h"
#include "math/Frame.h"
#include "math/Warp.h"
#include "shading/ConnectionBound.h"
#include "shading/DeltaChain.h"
#include "shading/Scattering.h"

namespace igi {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();
// lobe, 2 direction, 3 light sample, roulette, the BRDF lobe of the direction
constexpr std::uint32_t kDimsPerBounce = 8;

}  // namespace

PathIntegrator::PathIntegrator(const TraceableScene& scene, const Lights& lights,
                               const RenderSettings& settings, const CameraModel& camera)
    : scene_(scene), lights_(lights), settings_(settings), camera_(camera) {}

glm::vec3 PathIntegrator::shade(int x, int y, std::uint32_t pixelIndex, std::uint32_t frame,
                                RayCounters& counters) const {
    const auto spp = std::uint32_t(std::max(1, settings_.pathSamples));
    glm::vec3 sum(0.0f);
    for (std::uint32_t s = 0; s < spp; ++s)
        sum += tracePath(x, y, pixelIndex, frame * spp + s, counters);
    return sum / float(spp);
}

glm::vec3 PathIntegrator::tracePath(int x, int y, std::uint32_t pixelIndex,
                                    std::uint32_t sampleIndex, RayCounters& counters) const {
    const PixelSampler sampler(settings_.seed, SampleStream::PathTracer, pixelIndex, sampleIndex);
    glm::vec3 direction = camera_.direction(float(x) + sampler.get(0), float(y) + sampler.get(1));
    glm::vec3 origin = camera_.origin();
    glm::vec3 radiance(0.0f), beta(1.0f);
    bool lastWasNonDelta = false;
    float etaScale = 1.0f;  // 1 / the radianceScale factors of the refractions so far
    float lastPdf = 0;      // solid-angle density of the last non-delta bounce's direction
    glm::vec3 lastPosition(0.0f), lastNormal(0.0f);  // where it was sampled (the light tree's)
    SurfacePoint hit;
    for (int depth = 0; depth < settings_.maxPathLength; ++depth) {
        if (!scene_.intersect(origin, direction, kInfinity, hit, counters)) {
            // The sky: seen directly and through mirrors whole, else weighed against the
            // light samples that could have chosen it (the environment and each sun's disk).
            if (!lastWasNonDelta) {
                const glm::vec3 whole = scene_.skyRadiance(direction);
                if (!isBlack(whole)) radiance += beta * whole;
                break;
            }
            const glm::vec3 sky = scene_.environment().radiance(direction);
            if (!isBlack(sky))
                radiance += beta * sky *
                            powerHeuristic(lastPdf, lights_.environmentPdfAt(
                                                        lastPosition, lastNormal, direction));
            if (lights_.hasSuns())
                radiance += beta * lights_.sunsSeenByBrdf(lastPosition, lastNormal, direction,
                                                          lastPdf, 1.0f);
            break;
        }
        const glm::vec3 wo = -direction;
        const glm::vec3 le = emittedToward(hit, wo);
        if (!isBlack(le)) {
            float weight = 1.0f;
            if (lastWasNonDelta) {  // the light could also have been sampled directly
                const float cosLight = glm::dot(wo, hit.geometricNormal);
                const float lightPdf =
                    lights_.areaPdfAt(hit.mesh, hit.triangle, lastPosition, lastNormal) *
                    hit.distance * hit.distance / std::max(cosLight, 1e-8f);
                weight = powerHeuristic(lastPdf, lightPdf);
            }
            radiance += beta * le * weight;
        }
        const Lobes lobes = lobesAt(hit, wo);
        const std::uint32_t dim = 2 + kDimsPerBounce * std::uint32_t(depth);
        Lobe lobe;
        float probability = 0;
        if (!chooseLobe(lobes, sampler.get(dim), lobe, probability)) break;
        const glm::vec2 u(sampler.get(dim + 1), sampler.get(dim + 2));
        if (!isDelta(lobe)) {
            // The non-delta lobes together (chosen with probability pNonDelta): next-event
            // estimation toward one light sample and a direction from the BRDF, weighted
            // against each other by multiple importance sampling.
            const SurfaceBrdf& b = lobes.brdf;
            const float pNonDelta = nonDeltaProbability(lobes);
            radiance += beta / pNonDelta *
                        directLight(hit, lobes, sampler.get(dim + 3),
                                    {sampler.get(dim + 4), sampler.get(dim + 5)}, counters);
            direction = b.sample(u, sampler.get(dim + 7));
            const float cosX = glm::dot(direction, b.normal);
            if (cosX <= 0 || glm::dot(direction, lobes.faceNormal) <= 0) break;
            const float pdf = b.pdf(direction);
            if (!(pdf > 0)) break;
            const glm::vec3 f = b.diffuse() + b.glossy(direction);
            beta *= f * (cosX / (pdf * pNonDelta));
            lastWasNonDelta = true;
            lastPdf = pdf;
            lastPosition = hit.position;
            lastNormal = b.normal;
        } else if (lobes.roughGlass()) {
            // Rough glass (its only lobe): a light sample through its BSDF, on either side, and
            // a direction sampled from it, weighted against each other as the BRDF's are.
            radiance += beta / probability *
                        roughGlassLight(scene_, lights_, hit, lobes, sampler.get(dim + 3),
                                        {sampler.get(dim + 4), sampler.get(dim + 5)},
                                        RoughGlassLights::All, counters);
            glm::vec3 weight;
            if (!sampleLobe(lobes, lobe, u, sampler.get(dim + 7), direction, weight)) break;
            const float pdf = roughGlassPdf(lobes, direction);
            if (!(pdf > 0)) break;
            const float scale = radianceScale(lobes, direction);
            beta *= weight * (scale / probability);
            etaScale /= scale;
            lastWasNonDelta = true;
            lastPdf = pdf;
            lastPosition = hit.position;
            lastNormal = glm::vec3(0.0f);  // its light sample chose on both sides (RoughGlassLight)
        } else {
            glm::vec3 weight;
            if (!sampleLobe(lobes, lobe, u, 0.5f, direction, weight)) break;
            const float scale = radianceScale(lobes, direction);
            beta *= weight * (scale / probability);
            etaScale /= scale;
            lastWasNonDelta = false;
        }
        origin = scene_.offsetOrigin(hit.position, lobes.faceNormal, direction);
        if (depth >= 3) {  // Russian roulette once the path has had its main bounces
            // On the throughput without refraction's eta^2 (as pbrt-v4's etaScale): inside
            // glass the radiance is compressed, not the path's chance of adding light.
            const float q = std::min(0.95f, maxComponent(beta) * etaScale);
            if (sampler.get(dim + 6) >= q) break;
            beta /= q;
        }
        if (!isFinite(beta)) break;
    }
    return radiance;
}

glm::vec3 PathIntegrator::directLight(const SurfacePoint& hit, const Lobes& lobes, float uSelect,
                                      glm::vec2 uPoint, RayCounters& counters) const {
    // One light chosen among the receivers' and each exact light (a soft sun's disk point by
    // the same uPoint: each estimate is unbiased on its own).
    glm::vec3 sum = lightSample(
        hit, lobes, lights_.sampleAt(hit.position, lobes.brdf.normal, uSelect, uPoint), counters);
    for (std::size_t k = 0; k < lights_.exactLights(); ++k)
        sum += lightSample(hit, lobes, lights_.exactLight(k, uPoint), counters);
    return sum;
}

glm::vec3 PathIntegrator::lightSample(const SurfacePoint& hit, const Lobes& lobes,
                                      const LightSample& ls, RayCounters& counters) const {
    if (!(ls.pdf > 0)) return glm::vec3(0.0f);
    const glm::vec3 shadowOrigin = scene_.offsetOrigin(hit.position, lobes.faceNormal);
    const glm::vec3 toLight = ls.position - shadowOrigin;
    const float d2 = glm::dot(toLight, toLight);
    const float d = std::sqrt(d2);
    if (!(d > 0)) return glm::vec3(0.0f);
    const glm::vec3 w = toLight / d;
    const SurfaceBrdf& b = lobes.brdf;
    const float cosX = glm::dot(w, b.normal);
    const float cosY = !ls.isPoint ? -glm::dot(w, ls.normal)
                       : ls.spot   ? spotRamp(ls.cosOuter, ls.spotScale, -glm::dot(w, ls.normal))
                                   : 1.0f;
    if (cosX <= 0 || cosY <= 0 || glm::dot(w, lobes.faceNormal) <= 0) return glm::vec3(0.0f);
    const glm::vec3 target = ls.isPoint ? ls.position : scene_.offsetOrigin(ls.position, ls.normal);
    const float distance = glm::length(target - shadowOrigin);
    if (scene_.occluded(shadowOrigin, w, distance * (1.0f - 1e-4f), counters))
        return glm::vec3(0.0f);
    const glm::vec3 f = b.diffuse() + b.glossy(w);
    if (ls.isPoint) return f * ls.emitted * (cosX * cosY / (d2 * ls.pdf));
    const float lightPdf = ls.pdf * d2 / cosY;  // solid angle
    const float weight = powerHeuristic(lightPdf, b.pdf(w));
    return f * ls.emitted * (cosX * weight / lightPdf);
}

}  // namespace igi
