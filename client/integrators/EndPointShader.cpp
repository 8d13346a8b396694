#include "integrators/EndPointShader.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include <glm/geometric.hpp>

#include "lighting/LambertianLinks.h"
#include "math/Color.h"
#include "math/Warp.h"
#include "shading/ConnectionBound.h"
#include "shading/DeltaChain.h"

namespace igi {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// The part of a connection arriving from a direction of sharpness s that the bound removed,
// for a point reached by a compensation ray (`residual`); 1 otherwise.
float residualWeight(const ConnectionBound* residual, float sharpness) {
    return residual ? 1.0f - residual->kept(sharpness) : 1.0f;
}

// A connection's geometry: unit direction from the point to the VPL, distance and both cosines.
struct Link {
    glm::vec3 w;
    float d, d2, cosX, cosY;
};

// The link from `origin` (shading normal n, face normal f) to v, into `out`; false where v is
// behind the point or faces away from it (an omni light sample faces every way). Written into
// the caller's Link rather than returned as a std::optional: GCC moved that optional through
// the stack with loads wider than the stores that wrote it, a store-forwarding stall that
// cost a tenth of connectVpl's time.
bool linkTo(const Vpl& v, glm::vec3 origin, glm::vec3 n, glm::vec3 f, Link& out) {
    const glm::vec3 toLight = v.position - origin;
    const float d2 = glm::dot(toLight, toLight);
    if (!(d2 > 0)) return false;
    const float d = std::sqrt(d2);
    const glm::vec3 w = toLight / d;
    const float cosX = glm::dot(n, w);
    if (cosX <= 0 || glm::dot(f, w) <= 0) return false;
    const float cosY = v.emittingCosine(w);
    if (cosY <= 0) return false;
    out.w = w;
    out.d = d;
    out.d2 = d2;
    out.cosX = cosX;
    out.cosY = cosY;
    return true;
}

float maxSharpnessOf(const std::vector<Material>& materials, const std::vector<Texture>& textures) {
    float s = 1.0f;
    for (const Material& m : materials) {
        if (m.glass) continue;
        if (m.reflection == Reflection::Glossy && !isBlack(m.specular))
            s = std::max(s, 0.5f * (m.phongExponent + 2.0f));
        // A GGX material whose factor is under the mirror threshold is a mirror at every texel
        // (the map only scales it down); otherwise its smoothest GGX texel is its sharpest lobe.
        if (m.reflection == Reflection::Ggx && m.roughness * m.roughness >= ggx::kMinAlpha) {
            float roughness = std::clamp(m.roughness, 0.0f, 1.0f);
            if (m.metallicRoughnessTexture >= 0)
                roughness *= std::clamp(textures[m.metallicRoughnessTexture].minimum.y, 0.0f, 1.0f);
            s = std::max(s, ggx::maxSharpness(std::max(roughness * roughness, ggx::kMinAlpha)));
        }
    }
    return s;
}

/// The links LambertianLinks keeps from `origin` to the first `count` VPLs laid out in `lanes`,
/// in a buffer of the calling thread's that the next call overwrites.
const LinkBuffer& linksOf(const VplChoice& lanes, std::size_t count, glm::vec3 origin, glm::vec3 n,
                          glm::vec3 f, float dmin2) {
    thread_local LinkBuffer links;
    lambertianLinks(lanes, count, origin, n, f, dmin2, links);
    return links;
}

/// Queues every link of `links` as a Lambertian connection to `vpls[link.vpl]` (target
/// `first + link.vpl`): the scalar connection's arithmetic, for sets in which no link needs the
/// general one (VplChoice::anyGeneral false).
void queueLinks(const LinkBuffer& links, const std::vector<Vpl>& vpls, std::uint32_t first,
                ShadowQueue& queue) {
    queue.addEach(links.size(), [&](std::size_t k) {
        const LambertianLink link = links[k];
        return ShadowQueue::Connection{first + link.vpl, link.w, link.d * (1.0f - kVplShadowShrink),
                                       vpls[link.vpl].power * link.g, glm::vec3(0.0f)};
    });
}

}  // namespace

EndPointShader::EndPointShader(const TraceableScene& scene, const Lights& lights,
                               const RenderSettings& settings)
    : scene_(scene),
      lights_(lights),
      directSamples_(std::max(0, settings.directSamples)),
      maxEyeDepth_(settings.maxEyeDepth),
      compensate_(settings.clampCompensation == ClampCompensation::KolligKeller),
      maxSharpness_(maxSharpnessOf(scene.materials(), scene.textures())) {}

ShadowQueue& EndPointShader::scratchQueue(int depth) {
    // One queue per depth and thread: a point's continuation shades the next point (one level
    // deeper) before the point's own queue is summed.
    thread_local ShadowQueue queues[kMaxDepth + 1];
    ShadowQueue& q = queues[std::clamp(depth, 0, kMaxDepth)];
    q.clear();
    return q;
}

EndPointLight EndPointShader::shadeAt(const ShadingPoint& x, const LightingSet& set,
                                      PathRandom* random, int depth,
                                      const ConnectionBound* residual,
                                      RayCounters& counters) const {
    ShadowQueue& queue = scratchQueue(depth);
    Pending pending;
    queueAt(x, set, random != nullptr, depth, residual, queue, pending);
    queue.trace(scene_, counters);
    return finishAt(x, set, random, depth, residual, pending, queue, counters);
}

void EndPointShader::queueAt(const ShadingPoint& x, const LightingSet& set, bool withRandom,
                             int depth, const ConnectionBound* residual, ShadowQueue& queue,
                             Pending& pending) const {
    pending = Pending{};
    const bool glossy = x.brdf.hasGlossy();
    pending.continuation = withRandom && depth < kMaxDepth &&
                           (glossy || (compensate_ && set.compensationShare > 0 &&
                                       set.minDistance2 > 0 && set.indirectLight));
    const glm::vec3 origin = scene_.offsetOrigin(x.position, x.faceNormal);
    pending.point = queue.beginPoint(origin);
    // The exact lights first: finish() sums the point's first exactEntries connections apart.
    const std::size_t before = queue.size();
    const auto exactTarget = std::uint32_t(set.direct.size() + set.indirect.size());
    for (std::size_t k = 0; k < set.exact.size(); ++k)
        connectLight(x, set.exact[k], exactTarget + std::uint32_t(k), 1.0f,
                     pending.continuation && glossy, origin, residual, queue);
    pending.exactEntries = std::uint32_t(queue.size() - before);
    pending.indirectFromMethod =
        queueConnections(x, set, pending.continuation && glossy, residual, queue);
}

EndPointLight EndPointShader::finishAt(const ShadingPoint& x, const LightingSet& set,
                                       PathRandom* random, int depth,
                                       const ConnectionBound* residual, const Pending& pending,
                                       const ShadowQueue& queue, RayCounters& counters) const {
    Sums sums;
    glm::vec3 sharpIrradiance(0.0f), sharpGlossy(0.0f);
    queue.sum(pending.point, pending.exactEntries, sharpIrradiance, sharpGlossy, sums.irradiance,
              sums.glossy);
    // Lambertian indirect light from the method's records (instant caching, photon map).
    if (pending.indirectFromMethod)
        sums.irradiance += set.indirectIrradiance->irradiance(x.position, x.faceNormal, counters);
    // Light that came through mirrors and glass: the photons carry it to the Lambertian lobe;
    // to the glossy lobe only when no continuation looks at the mirrors and glass itself.
    const bool glossy = x.brdf.hasGlossy();
    gatherPhotons(x, set, glossy && !pending.continuation, residual, sums);
    if (pending.continuation) continueFrom(x, set, *random, depth, residual, sums, counters);
    return {sums.irradiance * kInvPi, sums.glossy, sharpIrradiance * kInvPi, sharpGlossy};
}

inline void EndPointShader::connectLight(const ShadingPoint& x, const Vpl& v, std::uint32_t target,
                                         float lightSamples, bool mis, glm::vec3 origin,
                                         const ConnectionBound* residual,
                                         ShadowQueue& queue) const {
    // Direct light: not bounded (its singularity is the light's own size, and for a glossy
    // lobe the MIS weight takes the light samples out where BRDF sampling is better).
    const SurfaceBrdf& b = x.brdf;
    const bool glossy = b.hasGlossy();
    Link link;
    if (!linkTo(v, origin, b.normal, x.faceNormal, link)) return;
    const glm::vec3 w = link.w;
    const float d = link.d, d2 = link.d2, cosX = link.cosX, cosY = link.cosY;
    // The lobe toward w once for the sharpness, density and value below.
    const float lobeW = glossy || residual ? b.lobeToward(w) : 0.0f;
    const float r = residual ? residualWeight(residual, b.sharpness(w, lobeW)) : 1.0f;
    if (!(r > 0)) return;
    const glm::vec3 e = v.power * (cosX * cosY / d2 * r);
    glm::vec3 g(0.0f);
    if (glossy) {
        float weight = 1.0f;
        if (mis && !v.omni)
            weight = powerHeuristic(lightSamples * v.areaPdf * d2 / cosY, b.pdf(w, lobeW));
        g = e * b.glossy(w, lobeW) * weight;
    }
    queue.add(target, w, d * (1.0f - kVplShadowShrink), e, g);
}

bool EndPointShader::queueConnections(const ShadingPoint& x, const LightingSet& set,
                                      bool misWithContinuation, const ConnectionBound* residual,
                                      ShadowQueue& queue) const {
    const SurfaceBrdf& b = x.brdf;
    const bool glossy = b.hasGlossy();
    const glm::vec3 n = b.normal;
    const glm::vec3 origin = scene_.offsetOrigin(x.position, x.faceNormal);
    const float lightSamples = float(directSamples_);
    auto connect = [&](std::uint32_t target, glm::vec3 w, float d, glm::vec3 e, glm::vec3 g) {
        queue.add(target, w, d * (1.0f - kVplShadowShrink), e, g);
    };

    auto addDirect = [&](const Vpl& v, std::uint32_t target) {
        connectLight(x, v, target, lightSamples, misWithContinuation, origin, residual, queue);
    };
    if (!glossy && residual == nullptr && set.directLanes.laidOut(set.direct.size())) {
        // A Lambertian point tests its light samples many at a time (LambertianLinks) with
        // addDirect's arithmetic: r is 1 and the bound's distance 0, so g is cos cos / d^2 as
        // there. Point lights (omni: a cosine of 1) are listed for addDirect itself.
        const LinkBuffer& links =
            linksOf(set.directLanes, set.direct.size(), origin, n, x.faceNormal, 0.0f);
        if (!set.directLanes.anyGeneral)  // no point lights: every link is connected alike
            queueLinks(links, set.direct, 0, queue);
        else
            for (std::size_t k = 0; k < links.size(); ++k) {
                const LambertianLink link = links[k];
                const Vpl& v = set.direct[link.vpl];
                if (v.omni)
                    addDirect(v, link.vpl);
                else
                    connect(link.vpl, link.w, link.d, v.power * link.g, glm::vec3(0.0f));
            }
    } else {
        for (std::size_t i = 0; i < set.direct.size(); ++i)
            addDirect(set.direct[i], std::uint32_t(i));
    }
    // With a light tree the point turns the set's numbers into light samples of its own.
    LightTree::Memo memo;
    for (const glm::vec3& u : set.directNumbers) {
        const LightSample s = lights_.sampleAt(x.position, n, u.x, {u.y, u.z}, &memo);
        if (s.pdf > 0)
            addDirect(directLightVpl(s, scene_, directSamples_), ShadowQueue::kOwnTarget);
    }

    // Indirect light: every connection bounded, through the BRDFs at both ends; at a
    // Lambertian point, from the method's records where it keeps them (instant caching).
    const bool lambertian = !glossy && residual == nullptr;
    // A glossy point's Lambertian lobe too, where the method has no VPLs for its glossy lobe
    // (that lobe's continuation ray takes the surfaces' radiance from the method instead).
    if (residual == nullptr && set.indirectIrradiance && (!glossy || set.indirect.empty()))
        return true;
    const bool clamp = set.boundShape == BoundShape::Clamp;
    if (!set.vplChoice.active(set.indirect.size())) {
        if (lambertian && clamp && set.vplChoice.laidOut(set.indirect.size()))
            connectLambertian(x, set, origin, queue);
        else
            for (std::size_t j = 0; j < set.indirect.size(); ++j)
                connectVpl(x, set, j, 1.0f, origin, residual, queue);
        return false;
    }
    // A few of the pool's VPLs, chosen by what each could give this point.
    thread_local std::vector<VplChoice::Pick> picks;
    picks.resize(set.vplChoice.perPoint);
    const std::uint32_t chosen =
        set.vplChoice.choose(origin, n, x.faceNormal, set.minDistance2, picks.data(), &b);
    for (std::uint32_t k = 0; k < chosen; ++k)
        connectVpl(x, set, picks[k].index, picks[k].scale, origin, residual, queue);
    return false;
}

void EndPointShader::connectVpl(const ShadingPoint& x, const LightingSet& set, std::size_t j,
                                float scale, glm::vec3 origin, const ConnectionBound* residual,
                                ShadowQueue& queue) const {
    const SurfaceBrdf& b = x.brdf;
    const bool glossy = b.hasGlossy();
    const glm::vec3 n = b.normal;
    const Vpl& v = set.indirect[j];
    const auto target = std::uint32_t(set.direct.size() + j);
    auto connect = [&](glm::vec3 w, float d, glm::vec3 e, glm::vec3 g) {
        queue.add(target, w, d * (1.0f - kVplShadowShrink), e, g);
    };
    // Indirect VPLs are never omni: linkTo takes the cosine at the VPL.
    Link link;
    if (!linkTo(v, origin, n, x.faceNormal, link)) return;
    const glm::vec3 w = link.w;
    const float d = link.d, d2 = link.d2, cosX = link.cosX, cosY = link.cosY;
    if (!glossy && residual == nullptr && set.boundShape == BoundShape::Clamp && !v.glossy()) {
        // Lambertian at both ends (sharpness 1, within any budget): the paper's clamp,
        // G <= cos cos / dmin^2. The common case, kept apart for speed.
        const float g = cosX * cosY / std::max(d2, set.minDistance2);
        glm::vec3 e = v.power * g;
        if (scale != 1.0f) e *= scale;
        connect(w, d, e, glm::vec3(0.0f));
        return;
    }
    const auto [intensity, sharpnessY] = v.towards(w);
    const float lobeW = glossy ? b.lobeToward(w) : 0.0f;  // once for the sharpness and value
    const float sharpnessX = glossy ? b.sharpness(w, lobeW) : b.diffuseShare;
    const float kept = keptFraction(d2, set.minDistance2, set.sharpnessBudget, sharpnessX,
                                    sharpnessY, set.boundShape);
    const float r = residualWeight(residual, sharpnessX);
    if (!(r > 0)) return;
    glm::vec3 e = intensity * (cosX * cosY / d2 * kept * r);
    if (scale != 1.0f) e *= scale;
    const glm::vec3 g = glossy ? e * b.glossy(w, lobeW) : glm::vec3(0.0f);
    connect(w, d, e, g);
}

void EndPointShader::connectLambertian(const ShadingPoint& x, const LightingSet& set,
                                       glm::vec3 origin, ShadowQueue& queue) const {
    // Every VPL of the set, tested many at a time with the scalar connection's arithmetic
    // (LambertianLinks), so that every value has the same bits as there.
    const auto first = std::uint32_t(set.direct.size());
    const LinkBuffer& links = linksOf(set.vplChoice, set.indirect.size(), origin, x.brdf.normal,
                                      x.faceNormal, set.minDistance2);
    if (!set.vplChoice.anyGeneral) {  // no glossy VPL: every link is connected alike
        queueLinks(links, set.indirect, first, queue);
        return;
    }
    for (std::size_t k = 0; k < links.size(); ++k) {
        const LambertianLink link = links[k];
        const Vpl& vpl = set.indirect[link.vpl];
        if (vpl.glossy() || vpl.bends) {  // the general connection, as the scalar path takes it
            connectVpl(x, set, link.vpl, 1.0f, origin, nullptr, queue);
            continue;
        }
        queue.add(first + link.vpl, link.w, link.d * (1.0f - kVplShadowShrink), vpl.power * link.g,
                  glm::vec3(0.0f));
    }
}

void EndPointShader::gatherPhotons(const ShadingPoint& x, const LightingSet& set, bool withGlossy,
                                   const ConnectionBound* residual, Sums& sums) const {
    const SurfaceBrdf& b = x.brdf;
    for (const CausticGrid* grid : {&set.caustics, &set.indirectCaustics}) {
        if (grid->photons().empty()) continue;
        const float r = grid->radius();
        const float density = 1.0f / (kPi * r * r);
        grid->forEachNear(x.position, [&](const CausticPhoton& p) {
            if (glm::dot(p.direction, b.normal) >= 0) return;  // arrived on the other side
            const glm::vec3 wi = -p.direction;
            const float weight =
                density * (residual ? residualWeight(residual, b.sharpness(wi)) : 1.0f);
            sums.irradiance += p.power * weight;
            if (withGlossy) sums.glossy += p.power * b.glossy(wi) * weight;
        });
    }
}

void EndPointShader::continueFrom(const ShadingPoint& x, const LightingSet& set, PathRandom& random,
                                  int depth, const ConnectionBound* residual, Sums& sums,
                                  RayCounters& counters) const {
    const SurfaceBrdf& b = x.brdf;
    const bool glossy = b.hasGlossy();
    // Without a glossy lobe the ray is for the compensation alone, a small correction near
    // creases: only a share of the points trace it, weighted up (Russian roulette).
    float traced = 1.0f;
    if (!glossy) {
        if (random.next() >= set.compensationShare) return;
        traced = set.compensationShare;
    }
    const glm::vec2 u = random.next2();
    const float uLobe = glossy ? random.next() : 0.0f;
    const float uChain = glossy ? random.next() : 0.0f;
    const glm::vec3 w = b.sample(u, uLobe);
    const float cosX = glm::dot(w, b.normal);
    if (cosX <= 0 || glm::dot(w, x.faceNormal) <= 0) return;
    const float lobeW = b.lobeToward(w);  // once for the density, sharpness and value
    const float pdf = b.pdf(w, lobeW);
    if (!(pdf > 0)) return;
    const float sharpnessX = b.sharpness(w, lobeW);
    const float r = residualWeight(residual, sharpnessX);
    if (!(r > 0)) return;
    const float scale = cosX / (pdf * traced) * r;  // radiance from w times this estimates E
    const glm::vec3 glossyF = glossy ? b.glossy(w, lobeW) : glm::vec3(0.0f);
    const bool compensate =
        compensate_ && set.compensationRays && set.minDistance2 > 0 && set.indirectLight;

    // Without a glossy lobe only the compensation needs the ray, and it has nothing to add
    // beyond dmin sqrt(s_x s_max), where every connection is kept whole.
    float tfar = kInfinity;
    if (!glossy) {
        if (!compensate) return;
        tfar = std::sqrt(set.minDistance2 * ConnectionBound::atLeastLambertian(sharpnessX) *
                         maxSharpness_ * ConnectionBound::reach2(set.boundShape));
    }
    const glm::vec3 origin = scene_.offsetOrigin(x.position, x.faceNormal, w);
    SurfacePoint hit;
    if (!scene_.intersect(origin, w, tfar, hit, counters)) {
        // The sky seen by the glossy lobe: the BRDF-sampling half of the MIS pair again, for
        // the environment and for each sun's disk, each against its own light samples.
        if (glossy) {
            const glm::vec3 sky = scene_.environment().radiance(w);
            if (!isBlack(sky)) {
                const float lightPdf = lights_.environmentPdfAt(x.position, b.normal, w);
                const float mis = powerHeuristic(pdf, float(directSamples_) * lightPdf);
                sums.glossy += sky * glossyF * (scale * mis);
            }
            if (lights_.hasSuns())
                sums.glossy +=
                    lights_.sunsSeenByBrdf(x.position, b.normal, w, pdf, float(directSamples_)) *
                    glossyF * scale;
        }
        return;
    }
    const glm::vec3 wy = -w;
    const float d2 = hit.distance * hit.distance;

    // A light seen by the glossy lobe: the BRDF-sampling half of the MIS pair.
    if (glossy) {
        const glm::vec3 le = emittedToward(hit, wy);
        if (!isBlack(le)) {
            const float cosLight = glm::dot(wy, hit.geometricNormal);
            const float lightPdf = lights_.areaPdfAt(hit.mesh, hit.triangle, x.position, b.normal) *
                                   d2 / std::max(cosLight, 1e-8f);
            const float mis = powerHeuristic(pdf, float(directSamples_) * lightPdf);
            sums.glossy += le * glossyF * (scale * mis);
        }
    }
    const Lobes lobes = lobesAt(hit, wy);

    // The light the surface it lands on sends back, where the method knows it (a photon map):
    // a glossy lobe has no VPLs of its own then.
    if (glossy && set.indirectIrradiance && set.indirectIrradiance->knowsSurfaceRadiance() &&
        lobes.hasNonDelta())
        sums.glossy +=
            glossyF * scale *
            set.indirectIrradiance->surfaceRadiance(hit.position, lobes.faceNormal, counters);

    // Kollig-Keller: the part of the connections between x and this point that the bound
    // removed, estimated with the point's own light, each incoming direction weighted by what
    // the bound removed of it.
    if (compensate && lobes.hasNonDelta()) {
        const ConnectionBound bound = ConnectionBound::of(d2, set.minDistance2, set.sharpnessBudget,
                                                          sharpnessX, set.boundShape);
        if (bound.cuts(lobes.brdf.maxSharpness())) {
            const EndPointLight l =
                shadeAt(ShadingPoint::at(hit, lobes), set, &random, depth + 1, &bound, counters);
            const glm::vec3 radiance = l.radiance(lobes.brdf) * scale;
            sums.irradiance += radiance;
            sums.glossy += radiance * glossyF;
        }
    }

    // The glossy lobe's view of mirrors and glass, followed to the next non-delta point (the
    // Lambertian lobe gets that light from the photons).
    if (!glossy || !lobes.hasDelta()) return;
    Lobe lobe;
    float probability = 0;
    if (!chooseDeltaLobe(lobes, uChain, lobe, probability)) return;
    glm::vec3 direction, weight;
    // Rough glass is sampled (with two more numbers, drawn only there), a delta lobe is not.
    const glm::vec2 uRough = lobes.roughGlass() ? random.next2() : glm::vec2(0.5f);
    if (!sampleLobe(lobes, lobe, uRough, remapChoice(uChain, probability), direction, weight))
        return;
    glm::vec3 emitted(0.0f);
    const glm::vec3 throughput =
        glossyF * (scale * radianceScale(lobes, direction) / probability) * weight;
    const auto end = followDeltaChain(
        scene_, scene_.offsetOrigin(hit.position, lobes.faceNormal, direction), direction,
        throughput, 0.0f, maxEyeDepth_, [&] { return random.next(); }, emitted, counters);
    sums.glossy += emitted;
    if (!end) return;
    const EndPointLight l =
        shadeAt(ShadingPoint::at(end->hit, end->lobes), set, &random, depth + 1, nullptr, counters);
    sums.glossy += end->throughput * l.radiance(end->lobes.brdf);
}

}  // namespace igi
