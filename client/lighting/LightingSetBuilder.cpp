#include "lighting/LightingSetBuilder.h"

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "lights/VplOnSurface.h"
#include "math/Color.h"
#include "math/Frame.h"
#include "math/Warp.h"
#include "render/ProgressiveSchedule.h"
#include "sampling/LightPathSampler.h"
#include "sampling/Sobol.h"
#include "shading/Scattering.h"

namespace igi {
namespace {

// Paths alive after each number of diffuse bounces in Keller's quasi-random walk: a fixed
// fraction rho (the scene's mean albedo) continues at each diffuse bounce, the lowest path
// indices first, so the count of VPLs is known in advance.
std::vector<std::uint32_t> survivorCounts(std::uint32_t paths, float rho, int maxLength) {
    std::vector<std::uint32_t> counts;
    double alive = paths;
    for (int d = 0; d + 1 < maxLength; ++d) {
        counts.push_back(std::uint32_t(std::lround(alive)));
        alive *= rho;
    }
    return counts;
}

std::uint32_t pathsFor(int wantedVpls, float rho, int maxLength) {
    if (wantedVpls <= 0 || maxLength < 2) return 0;
    for (std::uint32_t n = 1;; ++n) {
        std::uint32_t total = 0;
        for (std::uint32_t c : survivorCounts(n, rho, maxLength)) total += c;
        if (total >= std::uint32_t(wantedVpls)) return n;
    }
}

// A VPL where a light path carrying `flux` met a non-delta surface: it carries the surface's
// BRDF, seen from the direction the light came from.
Vpl vplAt(const TraceableScene& scene, const SurfacePoint& hit, const Lobes& lobes,
          glm::vec3 flux) {
    Vpl v = vplOnSurface(hit, lobes, flux);
    v.position = scene.offsetOrigin(hit.position, lobes.faceNormal);
    return v;
}

}  // namespace

LightingSetBuilder::LightingSetBuilder(const TraceableScene& scene, const Lights& lights,
                                       const RenderSettings& settings)
    : scene_(scene), lights_(lights), settings_(settings), caustics_(scene, lights, settings) {
    // With VPLs by importance each set keeps a pool, and each point connects to indirectVpls.
    // IGI's sets only: the other GI modes keep their VPLs (or records made from them) and
    // connect every one.
    if (settings.gi == GiMode::Igi && usesVplChoice(settings.vplSampling, lights.count()) &&
        settings.indirectVpls > 0)
        vplPool_ = settings.effectiveVplPool();
    vplPaths_ = settings.vplPaths > 0 ? std::uint32_t(settings.vplPaths)
                                      : pathsFor(vplPool_ > 0 ? vplPool_ : settings.indirectVpls,
                                                 scene.meanAlbedo(), settings.maxLightPathLength);
    survivors_ = survivorCounts(vplPaths_, scene.meanAlbedo(), settings.maxLightPathLength);
    minDistance_ = settings.clampDistance * scene.diagonal();
}

int LightingSetBuilder::maxLightPathLength(bool roulette) const {
    return roulette ? settings_.rouletteMaxLength : settings_.maxLightPathLength;
}

std::uint32_t LightingSetBuilder::survivors(std::uint32_t d) const {
    return d < survivors_.size() ? survivors_[d] : 0;
}

LightingSet LightingSetBuilder::build(std::uint32_t frame, std::uint32_t accumulation,
                                      std::uint32_t setIndex) const {
    return assemble(frame, accumulation, setIndex, true);
}

LightingSet LightingSetBuilder::buildDirect(std::uint32_t frame, std::uint32_t setIndex,
                                            bool caustics) const {
    return assemble(frame, 0, setIndex, false, caustics);
}

LightingSet LightingSetBuilder::buildWith(std::uint32_t frame, std::uint32_t setIndex,
                                          std::vector<Vpl> indirect, std::uint32_t paths) const {
    LightingSet set = buildDirect(frame, setIndex);
    set.indirect = std::move(indirect);
    set.indirectLight = !set.indirect.empty();
    set.lightPaths = paths;
    return set;
}

LightingSet LightingSetBuilder::assemble(std::uint32_t frame, std::uint32_t accumulation,
                                         std::uint32_t setIndex, bool lightPaths,
                                         bool caustics) const {
    LightingSet set;
    // The first frame after a change is what a user sees while moving. It has the light paths
    // and the bound of the frames after it (Russian roulette past the paper's walk; with the
    // compensation, the wider bound), measured against earlier builds' first frames in
    // docs/PERFORMANCE.md, "The first frame after a change".
    // What would restore the bound's cut (the compensation rays of the points without a glossy
    // lobe, and the second points the glossy ones shade) and the VPLs' photons cost rays and
    // time that one frame does not repay: they begin with the frames accumulated after it, so
    // the running mean converges all the same, the first frame's bias weighing 1 / frames.
    const bool accumulating = accumulation > 0;
    const bool compensate = settings_.clampCompensation == ClampCompensation::KolligKeller;
    set.roulette = settings_.roulette;
    set.compensationShare = compensate && accumulating ? kCompensationShare : 0.0f;
    // Progressive parts shrink with the frame's place in the accumulation.
    const double shrink = progressiveScale(settings_.progressiveAlpha, accumulation);
    set.minDistance2 = minDistance_ * minDistance_;
    // A glossy point's continuation ray still finds the lights its lobe sees in IGI's first
    // frame, but does not shade where it lands: that second point, with every light sample and
    // VPL again, took about half of the glossy room's first frame (measured by hand; the
    // report in docs/PERFORMANCE.md measures the frame as it now is).
    set.compensationRays = !(lightPaths && !accumulating);
    // The sharpness budget needs something to restore what it removes: without compensation a
    // glossy lobe is left whole (it is not singular, only noisy).
    if (compensate)
        set.sharpnessBudget = accumulating ? settings_.glossyBound : kFirstFrameSharpnessBudget;
    // The other GI modes' first frames, whose VPLs are given (buildWith, buildDirect), keep the
    // paper's bound: the first frame was measured with IGI's own light paths only.
    if (compensate && (accumulating || lightPaths))
        set.minDistance2 *= kCompensatedClampScale * kCompensatedClampScale;
    if (settings_.clampCompensation == ClampCompensation::Shrink) {
        set.minDistance2 = float(double(set.minDistance2) * shrink);
        set.sharpnessBudget = float(double(settings_.glossyBound) / shrink);
    }
    const double radiusShrink = settings_.progressiveRadius ? shrink : 1.0;
    if (lights_.empty()) return set;
    sampleDirect(frame, setIndex, set);
    set.directLanes.layOut(set.direct);
    if (lightPaths) walkLightPaths(frame, setIndex, set);
    // The VPLs laid out four-wide, for the connections (and with a pool, the choice among them).
    // Set k's offset in [k / K, (k + 1) / K): the frame's sets together stratify the choice over
    // the neighbouring pixels that the discontinuity buffer averages.
    const float u = Sobol::toFloat(scrambleBits(settings_.seed, frame, SampleStream::VplChoice, 0));
    const float sets = float(std::max(1, settings_.setCount()));
    set.vplChoice.prepare(set.indirect,
                          vplPool_ > 0 ? std::uint32_t(std::max(0, settings_.indirectVpls)) : 0,
                          std::min((float(setIndex) + u) / sets, 0.99999994f));
    std::uint32_t shot = 0;
    std::vector<CausticPhoton> photons;
    if (caustics && accumulating && settings_.poolCaustics) {
        // Accumulated frames gather every set's photons: the progressive filter withdraws the
        // discontinuity buffer's pooling where a caustic's edges show, and there each pixel
        // would otherwise see its own set's photons alone.
        photons = *pooledCaustics(frame, shot, set.buildRays);
    } else if (caustics) {
        photons = caustics_.shoot(frame, setIndex, shot, set.buildRays);
    }
    std::vector<CausticPhoton> indirectPhotons;
    if (accumulating)
        caustics_.shootFromVpls(frame, setIndex, set.indirect,
                                std::uint32_t(std::max(0, settings_.indirectCausticPhotons)),
                                indirectPhotons, shot, set.buildRays);
    set.photonsShot = shot;
    const double radiusScale = std::sqrt(radiusShrink);
    set.caustics = CausticGrid(std::move(photons), float(double(caustics_.radius()) * radiusScale));
    set.indirectCaustics = CausticGrid(
        std::move(indirectPhotons),
        float(double(settings_.indirectCausticRadius) * scene_.diagonal() * radiusScale));
    return set;
}

std::shared_ptr<const std::vector<CausticPhoton>> LightingSetBuilder::pooledCaustics(
    std::uint32_t frame, std::uint32_t& shot, RayCounters& rays) const {
    const auto sets = std::uint32_t(std::max(1, settings_.setCount()));
    std::shared_ptr<const Pool> pool;
    {
        std::lock_guard lock(poolMutex_);
        auto it = pools_.find(frame);
        if (it != pools_.end()) {
            pool = it->second;
        } else {
            auto made = std::make_shared<Pool>();
            const float share = 1.0f / float(sets);
            for (std::uint32_t k = 0; k < sets; ++k) {
                std::uint32_t n = 0;
                for (CausticPhoton p : caustics_.shoot(frame, k, n, made->rays)) {
                    p.power *= share;
                    made->photons.push_back(p);
                }
                made->shot += n;
            }
            // Tiles of a few frames are in flight at once; older frames are done.
            pools_.erase(pools_.begin(), pools_.lower_bound(frame > 8 ? frame - 8 : 0));
            pools_.emplace(frame, made);
            pool = made;
        }
    }
    shot = pool->shot / sets;
    rays += pool->rays.share(sets);
    return {pool, &pool->photons};
}

void LightingSetBuilder::sampleDirect(std::uint32_t frame, std::uint32_t setIndex,
                                      LightingSet& set) const {
    for (std::size_t k = 0; k < lights_.exactLights(); ++k) {
        // Each light its own scrambling of the sets' points: the sets of all k together
        // stratify a soft sun's disk.
        const auto d = std::uint32_t(2 * k);
        const glm::vec2 u(
            Sobol::scrambled(setIndex, 0,
                             scrambleBits(settings_.seed, frame, SampleStream::ExactLights, d)),
            Sobol::scrambled(
                setIndex, 1,
                scrambleBits(settings_.seed, frame, SampleStream::ExactLights, d + 1)));
        const LightSample s = lights_.exactLight(k, u);
        if (s.pdf > 0) set.exact.push_back(directLightVpl(s, scene_, 1));
    }
    if (!lights_.receiversChoose()) return;
    const auto n = std::uint32_t(std::max(0, settings_.directSamples));
    std::uint32_t scramble[3];
    for (std::uint32_t d = 0; d < 3; ++d)
        scramble[d] = scrambleBits(settings_.seed, frame, SampleStream::DirectLight, d);
    for (std::uint32_t j = 0; j < n; ++j) {
        // Set k owns points [k n, (k + 1) n): the sets of all k together stratify the lights.
        const std::uint32_t index = setIndex * n + j;
        const glm::vec3 u(Sobol::scrambled(index, 0, scramble[0]),
                          Sobol::scrambled(index, 1, scramble[1]),
                          Sobol::scrambled(index, 2, scramble[2]));
        // With a light tree each point chooses its own lights with the set's numbers, so the
        // sets still stratify the choice over neighbouring pixels, whose trees agree closely.
        if (lights_.choosesPerPoint()) {
            set.directNumbers.push_back(u);
            continue;
        }
        const LightSample s = lights_.sampleForReceivers(u.x, {u.y, u.z});
        if (s.pdf > 0) set.direct.push_back(directLightVpl(s, scene_, int(n)));
    }
}

void LightingSetBuilder::walkLightPaths(std::uint32_t frame, std::uint32_t setIndex,
                                        LightingSet& set) const {
    const bool roulette = set.roulette;
    const int maxLength = maxLightPathLength(roulette);
    if (vplPaths_ == 0 || maxLength < 2) return;
    set.indirectLight = true;
    const LightPathSampler sampler(settings_.seed, frame, SampleStream::VplPaths, setIndex,
                                   vplPaths_, std::uint32_t(maxLength));
    set.lightPaths = vplPaths_;
    traceLightPaths(sampler, PathEnd::KellerWalk, roulette, set.buildRays,
                    [&set](const Vpl& v) { set.indirect.push_back(v); });
}

std::vector<LightingSetBuilder::NamedVpl> LightingSetBuilder::namedVpls(SampleStream stream,
                                                                        std::uint32_t frame,
                                                                        bool roulette,
                                                                        std::uint32_t setIndex,
                                                                        RayCounters& rays) const {
    std::vector<NamedVpl> out;
    const int maxLength = maxLightPathLength(roulette);
    if (vplPaths_ == 0 || maxLength < 2 || lights_.empty()) return out;
    const LightPathSampler sampler(settings_.seed, frame, stream, setIndex, vplPaths_,
                                   std::uint32_t(maxLength));
    std::uint32_t path = 0, vertex = 0;
    traceLightPaths(
        sampler, PathEnd::KellerWalk, roulette, rays,
        [&](const Vpl& v) {
            out.push_back({vplId(setIndex, path, vertex), v});
        },
        [&](std::uint32_t j, const SurfacePoint&) {
            if (j != path) path = j, vertex = 0;
            ++vertex;
        });
    return out;
}

void LightingSetBuilder::traceLightPaths(const LightPathNumbers& sampler, PathEnd end,
                                         bool roulette, RayCounters& rays,
                                         const std::function<void(const Vpl&)>& deposit,
                                         const Visit& visit) const {
    const std::uint32_t paths = sampler.pathsPerSet();
    const int maxLength = maxLightPathLength(roulette);
    const float invPaths = 1.0f / float(paths);
    SurfacePoint hit;
    for (std::uint32_t j = 0; j < paths; ++j) {
        const LightSample light = lights_.sample(sampler.emission(j, 0),
                                                 {sampler.emission(j, 1), sampler.emission(j, 2)});
        if (!(light.pdf > 0)) continue;
        const glm::vec2 uDir(sampler.emission(j, 3), sampler.emission(j, 4));
        glm::vec3 origin, direction, beta;  // beta: the flux the path carries
        if (light.directional) {
            // Parallel light through the rectangle across it that the scene's box fills.
            direction = light.direction;
            const Lights::ParallelStart start = lights_.parallelStart(direction, uDir);
            origin = start.origin;
            beta = light.irradiance * start.area / light.select;
        } else if (light.spot) {
            // Uniform in the outer cone, weighted by the ramp.
            direction = Frame(light.normal).toWorld(squareToUniformCone(uDir, light.cosOuter));
            const float ramp =
                spotRamp(light.cosOuter, light.spotScale, glm::dot(direction, light.normal));
            origin = light.position;
            beta = light.emitted * (ramp / (uniformConePdf(light.cosOuter) * light.pdf));
        } else if (light.isPoint) {
            origin = light.position;
            direction = squareToUniformSphere(uDir);
            beta = light.emitted * (4.0f * kPi) / light.pdf;
        } else {
            // Cosine-distributed emission: Le cos / (pdf_A cos / pi) = Le pi / pdf_A.
            origin = scene_.offsetOrigin(light.position, light.normal);
            direction = Frame(light.normal).toWorld(squareToCosineHemisphere(uDir));
            beta = light.emitted * kPi / light.pdf;
        }
        std::uint32_t nonDeltaBounces = 0;
        bool russianRoulette = end == PathEnd::Roulette;  // past the paper's walk
        for (int vertex = 1; vertex < maxLength; ++vertex) {
            if (!scene_.intersect(origin, direction, std::numeric_limits<float>::infinity(), hit,
                                  rays))
                break;
            if (visit) visit(j, hit);
            const Lobes lobes = lobesAt(hit, -direction);
            // No VPL on mirrors or glass: what they reflect is the caustic photons' job.
            if (lobes.hasNonDelta()) deposit(vplAt(scene_, hit, lobes, beta * invPaths));
            if (vertex + 1 >= maxLength) break;
            Lobe lobe;
            float probability = 0;
            const auto v = std::uint32_t(vertex);
            const float uLobe = sampler.bounce(j, v, 2);
            if (!russianRoulette) {
                if (!chooseLobe(lobes, uLobe, lobe, probability)) break;
                if (!isDelta(lobe)) {
                    // Keller's quasi-random walk (the paper's): a fixed number of paths, the
                    // lowest indices, goes on at each non-delta bounce, carrying the weight of
                    // those that stopped. Stratified and cheap, but it ends at the paper's
                    // length; with roulette the paths still alive there go on by Russian
                    // roulette instead, so that no bounce is left out.
                    const std::uint32_t before = survivors(nonDeltaBounces),
                                        after = survivors(nonDeltaBounces + 1);
                    ++nonDeltaBounces;
                    if (after == 0 && roulette) {
                        russianRoulette = true;
                    } else {
                        if (j >= after) break;
                        beta *= float(before) / float(after);
                    }
                }
            }
            if (russianRoulette && !chooseLobe(lobes, uLobe, lobe, probability, true)) break;
            glm::vec3 weight;
            if (!sampleLobe(lobes, lobe, {sampler.bounce(j, v, 0), sampler.bounce(j, v, 1)},
                            remapChoice(uLobe, probability), direction, weight))
                break;
            beta *= weight / probability;
            if (isBlack(beta) || !isFinite(beta)) break;
            origin = scene_.offsetOrigin(hit.position, lobes.faceNormal, direction);
        }
    }
}

}  // namespace igi
