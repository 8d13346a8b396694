#include "integrators/IgiIntegrator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "math/Color.h"
#include "math/Warp.h"
#include "shading/ShadowQueue.h"

namespace igi {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

std::shared_ptr<const LightEdges> lightEdgesFor(const Lights& lights, const CameraModel& camera,
                                                const RenderSettings& settings) {
    return std::make_shared<const LightEdges>(
        settings.lightEdgeRays > 0 ? LightEdges(lights, camera) : LightEdges());
}

}  // namespace

glm::vec3 emittedToward(const SurfacePoint& hit, glm::vec3 wo) {
    if (!hit.material->isEmissive() || glm::dot(wo, hit.geometricNormal) <= 0)
        return glm::vec3(0.0f);
    return hit.material->emission * hit.emissionTexel;  // exactly `emission` without a texture
}

IgiIntegrator::IgiIntegrator(const TraceableScene& scene, const Lights& lights,
                             const RenderSettings& settings, const CameraModel& camera)
    : scene_(scene),
      lights_(lights),
      settings_(settings),
      camera_(camera),
      shader_(scene, lights, settings),
      lightEdges_(lightEdgesFor(lights, camera, settings)) {}

IgiIntegrator::IgiIntegrator(const IgiIntegrator& other, const RenderSettings& settings)
    : scene_(other.scene_),
      lights_(other.lights_),
      settings_(settings),
      camera_(other.camera_),
      shader_(scene_, lights_, settings),
      lightEdges_((settings.lightEdgeRays > 0) == (other.settings_.lightEdgeRays > 0)
                      ? other.lightEdges_
                      : lightEdgesFor(lights_, camera_, settings)) {}

/// One pixel's eye path through the phases of shade(): its numbers, the eye ray's hit, its end
/// points and what each queued.
struct IgiIntegrator::PixelPath {
    PixelSampler sampler{0, SampleStream::EyePath, 0, 0};
    std::uint32_t nextNumber = 2;  ///< 0 and 1: the position in the pixel
    glm::vec3 direction{0.0f};
    SurfacePoint hit;
    bool found = false;
    bool lightFromEdgeRays = false;   ///< the light seen directly comes from gatherLightAtEdges
    std::optional<ChainEnd> ends[3];  ///< the non-delta part, then the mirror and glass paths
    EndPointShader::Pending pending[3];
    int primary = -1;  ///< the end point the master filters
};

/// A ray leaving a pixel's first hit along a mirror or glass lobe, and where it landed.
struct IgiIntegrator::Continuation {
    int pixel = 0;  ///< in the pixels being shaded
    int end = 0;    ///< the PixelPath end it leads to: 1 mirror, 2 glass
    glm::vec3 origin{0.0f}, direction{0.0f}, weight{0.0f};
    SurfacePoint hit;
    bool found = false;
};

PixelResult IgiIntegrator::shade(int x, int y, std::uint32_t pixelIndex, std::uint32_t frame,
                                 const LightingSet& set, RayCounters& counters) const {
    const Pixel pixel{x, y, pixelIndex};
    PixelResult result;
    shade(&pixel, 1, frame, set, &result, counters);
    return result;
}

void IgiIntegrator::shade(const Pixel* pixels, int count, std::uint32_t frame,
                          const LightingSet& set, PixelResult* results,
                          RayCounters& counters) const {
    // Per thread, kept between calls: no allocation per chunk once warm.
    thread_local std::vector<PixelPath> paths;
    thread_local ShadowQueue queue;
    thread_local std::vector<float> px, py;
    thread_local std::vector<glm::vec3> directions;
    paths.resize(std::size_t(count));
    px.resize(std::size_t(count));
    py.resize(std::size_t(count));
    directions.resize(std::size_t(count));
    for (int i = 0; i < count; ++i) {
        PixelPath& p = paths[std::size_t(i)];
        // Reset field by field: a whole PixelPath{} would copy its three end points' storage.
        for (auto& e : p.ends) e.reset();
        p.found = false;
        p.primary = -1;
        p.nextNumber = 2;
        p.lightFromEdgeRays = false;
        p.sampler = PixelSampler(settings_.seed, SampleStream::EyePath, pixels[i].index, frame);
        px[std::size_t(i)] = float(pixels[i].x) + p.sampler.get(0);
        py[std::size_t(i)] = float(pixels[i].y) + p.sampler.get(1);
        results[i] = PixelResult{};
    }
    camera_.directions(px.data(), py.data(), count, directions.data());
    for (int i = 0; i < count; ++i) paths[std::size_t(i)].direction = directions[std::size_t(i)];
    traceEyeRays(paths.data(), count, counters);
    if (!lightEdges_->empty())
        gatherLightAtEdges(pixels, count, frame, paths.data(), results, counters);
    // The rays that leave the first hits along mirror and glass lobes go in packets too; the
    // rest of each chain follows one ray at a time (its numbers come from the pixel's stream,
    // in order).
    thread_local std::vector<Continuation> continuations;
    continuations.clear();
    const bool sky = scene_.hasSky();
    for (int i = 0; i < count; ++i) {
        const PixelPath& p = paths[std::size_t(i)];
        if (p.found)
            splitAtFirstHit(paths[std::size_t(i)], i, results[i], continuations, counters);
        else if (sky && !p.lightFromEdgeRays)  // the camera sees the sky, unfiltered
            results[i].unfiltered += scene_.skyRadiance(p.direction);
    }
    traceContinuations(continuations, counters);
    queue.clear();
    std::size_t next = 0;  // continuations are in pixel order
    for (int i = 0; i < count; ++i) {
        PixelPath& p = paths[std::size_t(i)];
        if (!p.found) continue;
        followChains(p, i, continuations, next, results[i], counters);
        for (int e = 0; e < 3; ++e)
            if (p.ends[e])
                shader_.queue(ShadingPoint::at(p.ends[e]->hit, p.ends[e]->lobes), set, queue,
                              p.pending[e]);
    }
    queue.trace(scene_, counters);
    for (int i = 0; i < count; ++i)
        if (paths[std::size_t(i)].primary >= 0)
            shadeEnds(paths[std::size_t(i)], set, queue, results[i], counters);
}

glm::vec3 IgiIntegrator::seenDirectly(bool found, const SurfacePoint& hit,
                                      glm::vec3 direction) const {
    if (found) return emittedToward(hit, -direction);
    return scene_.hasSky() ? scene_.skyRadiance(direction) : glm::vec3(0.0f);
}

void IgiIntegrator::gatherLightAtEdges(const Pixel* pixels, int count, std::uint32_t frame,
                                       PixelPath* paths, PixelResult* results,
                                       RayCounters& counters) const {
    const int k = settings_.lightEdgeRays;
    thread_local std::vector<int> marked;  // in the pixels being shaded
    thread_local std::vector<float> px, py;
    thread_local std::vector<glm::vec3> directions, seen;
    marked.clear();
    for (int i = 0; i < count; ++i)
        if (lightEdges_->contains(pixels[i].x, pixels[i].y)) marked.push_back(i);
    if (marked.empty()) return;
    const std::size_t rays = marked.size() * std::size_t(k);
    px.resize(rays);
    py.resize(rays);
    directions.resize(rays);
    seen.assign(marked.size(), glm::vec3(0.0f));
    for (std::size_t m = 0; m < marked.size(); ++m) {
        const Pixel& pixel = pixels[marked[m]];
        // The first k Sobol' points, with bits of this pixel and frame: stratified in the
        // pixel, and independent from frame to frame, so that the halves of the error estimate
        // (RowAccumulator::meanRow) see this light's noise as it is. (Points of one sequence
        // over the frames would converge faster but make the halves differ more than the mean
        // errs: docs/ERROR_ESTIMATE.md.)
        const std::uint64_t h =
            hashValues(settings_.seed, static_cast<std::uint32_t>(SampleStream::LightEdgeRays),
                       pixel.index, frame);
        for (int r = 0; r < k; ++r) {
            const std::size_t j = m * std::size_t(k) + std::size_t(r);
            px[j] = float(pixel.x) + Sobol::scrambled(std::uint32_t(r), 0, std::uint32_t(h));
            py[j] = float(pixel.y) + Sobol::scrambled(std::uint32_t(r), 1, std::uint32_t(h >> 32));
        }
        paths[marked[m]].lightFromEdgeRays = true;
    }
    camera_.directions(px.data(), py.data(), int(rays), directions.data());
    traceInPackets(
        int(rays),
        [&](int j) {
            return std::pair{camera_.origin(), directions[std::size_t(j)]};
        },
        [&](int j, bool found, const SurfacePoint& hit) {
            seen[std::size_t(j / k)] += seenDirectly(found, hit, directions[std::size_t(j)]);
        },
        counters, TraceableScene::HitDetail::Emission);  // seenDirectly reads no more
    for (std::size_t m = 0; m < marked.size(); ++m)
        results[marked[m]].unfiltered += seen[m] / float(k);
}

void IgiIntegrator::traceEyeRays(PixelPath* paths, int count, RayCounters& counters) const {
    traceInPackets(
        count,
        [&](int k) {
            return std::pair{camera_.origin(), paths[k].direction};
        },
        [&](int k, bool found, const SurfacePoint& hit) {
            paths[k].found = found;
            if (found) paths[k].hit = hit;
        },
        counters);
}

void IgiIntegrator::traceContinuations(std::vector<Continuation>& rays,
                                       RayCounters& counters) const {
    traceInPackets(
        int(rays.size()),
        [&](int k) {
            return std::pair{rays[k].origin, rays[k].direction};
        },
        [&](int k, bool found, const SurfacePoint& hit) {
            rays[k].found = found;
            if (found) rays[k].hit = hit;
        },
        counters);
}

template <class Ray, class Land>
void IgiIntegrator::traceInPackets(int count, Ray&& ray, Land&& land, RayCounters& counters,
                                   TraceableScene::HitDetail detail) const {
    const int width = scene_.packetWidth();
    glm::vec3 origins[TraceableScene::kMaxPacket], directions[TraceableScene::kMaxPacket];
    float tfar[TraceableScene::kMaxPacket];
    SurfacePoint hits[TraceableScene::kMaxPacket];
    bool found[TraceableScene::kMaxPacket];
    for (int begin = 0; begin < count; begin += width) {
        const int n = std::min(width, count - begin);
        for (int k = 0; k < n; ++k) {
            std::tie(origins[k], directions[k]) = ray(begin + k);
            tfar[k] = kInfinity;
        }
        if (n == 1)  // a packet of one ray costs more than the ray alone
            found[0] = scene_.intersect(origins[0], directions[0], kInfinity, hits[0], counters);
        else
            scene_.intersectPacket(origins, directions, tfar, n, hits, found, counters, detail);
        for (int k = 0; k < n; ++k) land(begin + k, found[k], hits[k]);
    }
}

void IgiIntegrator::splitAtFirstHit(PixelPath& p, int pixel, PixelResult& result,
                                    std::vector<Continuation>& continuations,
                                    RayCounters& counters) const {
    const SurfacePoint& hit = p.hit;
    const glm::vec3 wo = -p.direction;
    if (!p.lightFromEdgeRays) result.unfiltered += emittedToward(hit, wo);
    // The lobes are built in the non-delta end point's place (ChainEnd's constructor), which
    // is emptied again if they have no non-delta part; the delta lobes below read them there.
    const Lobes& lobes = p.ends[0].emplace(hit, wo, glm::vec3(1.0f), hit.distance).lobes;

    // Split once: the non-delta part here, and one path per delta component, whose first ray
    // (a delta lobe's direction takes no random numbers) is traced with the other pixels'.
    // Rough glass's one lobe (reflection and refraction) is sampled with the pixel's next
    // three numbers, which only such a hit draws.
    const Lobe deltas[2] = {Lobe::Reflection, Lobe::Transmission};
    for (int i = 0; i < 2 && settings_.maxEyeDepth >= 1; ++i) {
        glm::vec3 next, weight;
        if (lobeWeight(lobes, deltas[i]) <= 0) continue;
        glm::vec2 u(0.5f);
        float uChoice = 0.5f;
        if (deltas[i] == Lobe::Transmission && lobes.roughGlass()) {
            PathRandom random(p.sampler, p.nextNumber);
            u = random.next2();
            uChoice = random.next();
            if (lights_.hasDeltaLights())
                result.unfiltered += roughGlassDeltaLight(hit, lobes, random, counters);
            p.nextNumber = random.position();
        }
        if (!sampleLobe(lobes, deltas[i], u, uChoice, next, weight)) continue;
        Continuation c;
        c.pixel = pixel;
        c.end = i + 1;
        c.origin = scene_.offsetOrigin(hit.position, lobes.faceNormal, next);
        c.direction = next;
        c.weight = weight * radianceScale(lobes, next);  // radiance: refraction's eta^2
        continuations.push_back(c);
    }
    if (!lobes.hasNonDelta()) p.ends[0].reset();
}

glm::vec3 IgiIntegrator::roughGlassDeltaLight(const SurfacePoint& hit, const Lobes& lobes,
                                              PathRandom& random, RayCounters& counters) const {
    const float uSelect = random.next();
    const glm::vec2 uPoint = random.next2();
    return roughGlassLight(scene_, lights_, hit, lobes, uSelect, uPoint,
                           RoughGlassLights::DeltaOnly, counters);
}

void IgiIntegrator::followChains(PixelPath& p, int pixel,
                                 const std::vector<Continuation>& continuations, std::size_t& next,
                                 PixelResult& result, RayCounters& counters) const {
    PathRandom random(p.sampler, p.nextNumber);
    for (; next < continuations.size() && continuations[next].pixel == pixel; ++next) {
        const Continuation& c = continuations[next];
        if (!c.found) {
            result.unfiltered += c.weight * scene_.skyRadiance(c.direction);
            continue;
        }
        // Without delta lights nothing is drawn for them: such scenes keep their numbers.
        followDeltaChainInto(
            p.ends[c.end], scene_, c.hit, c.direction, c.weight, p.hit.distance,
            settings_.maxEyeDepth, [&] { return random.next(); }, result.unfiltered, counters,
            [&](const SurfacePoint& hit, const Lobes& lobes, glm::vec3 throughput) {
                if (lights_.hasDeltaLights())
                    result.unfiltered +=
                        throughput * roughGlassDeltaLight(hit, lobes, random, counters);
            });
    }
    p.nextNumber = random.position();

    // The end point that reflects most is the one the master filters.
    auto reflectance = [](const ChainEnd& e) {
        return luminance(e.throughput * (e.lobes.brdf.kd + e.lobes.brdf.glossyAlbedo()));
    };
    for (int i = 0; i < 3; ++i)
        if (p.ends[i] &&
            (p.primary < 0 || reflectance(*p.ends[i]) > reflectance(*p.ends[p.primary])))
            p.primary = i;
}

void IgiIntegrator::shadeEnds(PixelPath& p, const LightingSet& set, const ShadowQueue& queue,
                              PixelResult& result, RayCounters& counters) const {
    PathRandom random(p.sampler, p.nextNumber);
    for (int i = 0; i < 3; ++i) {
        if (!p.ends[i]) continue;
        const ChainEnd& e = *p.ends[i];
        const EndPointLight light = shader_.finish(ShadingPoint::at(e.hit, e.lobes), set, random,
                                                   p.pending[i], queue, counters);
        if (i == p.primary) {
            result.irradiance = light.irradiance;
            result.reflectance = e.throughput * e.lobes.brdf.kd;
            result.glossy = e.throughput * light.glossy;
            // The exact lights' light is the same in every set: filtering it would only blur
            // its shadow edges.
            result.unfiltered += e.throughput * light.sharpRadiance(e.lobes.brdf);
            result.normal = e.lobes.normal;
            result.depth = e.pathLength;
            result.firstHit = i == 0;
        } else {
            result.unfiltered += e.throughput * light.radiance(e.lobes.brdf);
        }
    }
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
    const EndPointLight light = shader_.shadeWithoutContinuation(p, set, counters);
    return light.irradiance + light.sharpIrradiance;
}

}  // namespace igi
