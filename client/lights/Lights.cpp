#include "lights/Lights.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>

#include <embree3/rtcore.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include "math/Color.h"
#include "math/Frame.h"
#include "math/Warp.h"
#include "shading/ConnectionBound.h"

namespace igi {
namespace {

std::uint64_t triangleKey(std::uint32_t mesh, std::uint32_t triangle) {
    return (std::uint64_t(mesh) << 32) | triangle;
}

// A triangle's corners from the smallest one on, in its own cyclic order: the same for the same
// triangle listed twice, whatever corner it starts from, but not for the reversed winding (which
// faces, and emits, the other way).
using Corners = std::array<float, 9>;
Corners cornersOf(const TraceableScene::WorldTriangle& t) {
    const glm::vec3 p[3] = {t.p0, t.p1, t.p2};
    auto key = [&](int first) {
        Corners c;
        for (int i = 0; i < 3; ++i)
            for (int k = 0; k < 3; ++k) c[3 * i + k] = p[(first + i) % 3][k];
        return c;
    };
    return std::min({key(0), key(1), key(2)});
}

// A sun of 1e5 lux beside a room's lamps would take nearly every choice by power (or the lamps
// every one of a dim sky's): when directional lights share a choice with others, half the choices
// are by power and half uniform over the lights that take part, so none is starved. `part` says
// which lights take part (the others get 0).
std::vector<float> choiceWeights(std::vector<float> power, const std::vector<bool>& part,
                                 const std::vector<bool>& parallel) {
    bool directional = false, finite = false;
    std::size_t n = 0;
    for (std::size_t i = 0; i < power.size(); ++i) {
        if (!part[i]) {
            power[i] = 0;
            continue;
        }
        ++n;
        (parallel[i] ? directional : finite) = true;
    }
    if (!directional || !finite) return power;
    double total = 0;
    for (float w : power) total += w;
    if (total > 0)
        for (std::size_t i = 0; i < power.size(); ++i)
            if (part[i]) power[i] = float(0.5 * double(power[i]) / total + 0.5 / double(n));
    return power;
}

EmissiveTexture emissiveTextureOf(const TraceableScene& traceable,
                                  const TraceableScene::WorldTriangle& t, const Material& m) {
    return EmissiveTexture(traceable.textures()[m.emissionTexture], m.emissionUv,
                           traceable.triangleUvs(t.mesh, t.triangle));
}

// The luminance a textured triangle's power is chosen by (emittedLuminance); `imageMaximum`
// keeps each texture's brightest texel, found once.
float texturedLuminance(const EmissiveTexture& texture, const Material& m,
                        const std::vector<Texture>& textures, std::map<int, float>& imageMaximum) {
    auto brightest = imageMaximum.find(m.emissionTexture);
    if (brightest == imageMaximum.end())
        brightest =
            imageMaximum.emplace(m.emissionTexture, maxTexelLuminance(textures[m.emissionTexture]))
                .first;
    return emittedLuminance(texture, m.emission, brightest->second);
}

}  // namespace

Lights::Lights(const TraceableScene& traceable, const std::vector<PunctualLight>& punctualLights,
               LightSampling sampling) {
    std::vector<float> power;
    // A face listed twice (duplicated in its file) is one surface, seen once: it must be one
    // light, or sampling it would count its light twice. The copy maps to the same emitter so that
    // a path that hits the copy finds the density of the light it is.
    std::map<Corners, std::uint32_t> emitterAt;
    std::map<int, float> imageMaximum;  // per emissive texture, found once
    for (const auto& t : traceable.emissiveTriangles()) {
        Emitter e;
        e.p0 = t.p0;
        e.e1 = t.p1 - t.p0;
        e.e2 = t.p2 - t.p0;
        const glm::vec3 c = glm::cross(e.e1, e.e2);
        const float len = glm::length(c);
        if (!(len > 0) || !std::isfinite(len)) continue;  // a degenerate triangle emits nothing
        const Material& material = traceable.materials()[t.material];
        e.emitted = material.emission;
        float emittedLum = luminance(e.emitted);
        if (material.emissionTexture >= 0) {
            e.texture = emissiveTextureOf(traceable, t, material);
            emittedLum = texturedLuminance(e.texture, material, traceable.textures(), imageMaximum);
            if (!(emittedLum > 0)) continue;  // black wherever it is: it emits nothing
        }
        const auto [it, fresh] =
            emitterAt.try_emplace(cornersOf(t), std::uint32_t(emitters_.size()));
        if (!fresh) {
            triangleToEmitter_[triangleKey(t.mesh, t.triangle)] = it->second;
            continue;
        }
        e.normal = c / len;
        e.area = 0.5f * len;
        triangleToEmitter_[triangleKey(t.mesh, t.triangle)] = std::uint32_t(emitters_.size());
        emitters_.push_back(e);
        power.push_back(kPi * e.area * emittedLum);  // one-sided Lambertian emitter
    }
    center_ = traceable.center();
    radius_ = 0.5f * traceable.diagonal();
    // The box Embree holds around everything a ray can meet (the placed objects).
    RTCBounds box;
    rtcGetSceneBounds(traceable.embreeScene(), &box);
    boxLo_ = {box.lower_x, box.lower_y, box.lower_z};
    boxHi_ = {box.upper_x, box.upper_y, box.upper_z};
    hasBox_ =
        glm::all(glm::lessThanEqual(boxLo_, boxHi_)) && std::isfinite(glm::length(boxHi_ - boxLo_));
    const float sunDistance = kSunDistance * radius_;
    std::vector<float> treePower = power;  // a directional light's is its far point's
    for (const PunctualLight& p : punctualLights) {
        if (!p.on) continue;
        Emitter e;
        e.p0 = p.position;
        e.emitted = p.intensity;
        e.normal = p.direction;
        if (p.kind == LightKind::Point) {
            e.kind = Kind::Point;
            power.push_back(4.0f * kPi * luminance(p.intensity));
        } else if (p.kind == LightKind::Spot) {
            e.kind = Kind::Spot;
            e.cosOuter = spotCosOuter(p);
            e.spotScale = spotScale(p);
            // At most the power of its outer cone at full intensity.
            power.push_back(2.0f * kPi * (1.0f - e.cosOuter) * luminance(p.intensity));
        } else {
            e.kind = Kind::Directional;
            e.oneMinusCos = sunOneMinusCos(p.angleDeg);
            e.sunScale = sunConeScale(e.oneMinusCos);
            hasDirectional_ = true;
            if (const std::optional<SunDisk> disk = sunDiskOf(p))
                suns_.push_back({*disk, std::uint32_t(emitters_.size())});
            // What crosses the disk of the scene's bounding sphere.
            power.push_back(kPi * radius_ * radius_ * luminance(p.intensity));
        }
        treePower.push_back(e.kind == Kind::Directional
                                ? 4.0f * kPi * luminance(p.intensity) * sunDistance * sunDistance
                                : power.back());
        // A sun with an angle is a disk in the sky (pointOn); the others are points.
        if (!(e.kind == Kind::Directional && e.oneMinusCos > 0)) hasDeltaLights_ = true;
        emitters_.push_back(e);
    }
    if (traceable.environment().present()) {
        environment_ = &traceable.environment();
        environmentIndex_ = std::uint32_t(emitters_.size());
        Emitter e;
        e.kind = Kind::Environment;
        emitters_.push_back(e);
        hasDirectional_ = true;
        // What crosses the disk of the bounding sphere from every direction: 4 pi A L_mean.
        const float mean = environment_->meanLuminance();
        power.push_back(4.0f * kPi * kPi * radius_ * radius_ * mean);
        // For the tree: a plane's irradiance under it (pi L_mean) at the far sphere's distance.
        treePower.push_back(4.0f * kPi * kPi * mean * sunDistance * sunDistance);
    }
    std::vector<bool> parallel(emitters_.size()), all(emitters_.size(), true);
    std::size_t punctual = 0;
    for (std::size_t i = 0; i < emitters_.size(); ++i) {
        parallel[i] =
            emitters_[i].kind == Kind::Directional || emitters_[i].kind == Kind::Environment;
        if (emitters_[i].isPoint()) ++punctual;
    }
    // Light paths choose among every light.
    distribution_ = Distribution1D(choiceWeights(power, all, parallel));
    // A few point, spot and sun lights are each a shadow ray of every receiver (exactLight):
    // receivers choose among the others.
    std::vector<bool> chosen = all;
    if (punctual <= kMaxExactLights)
        for (std::size_t i = 0; i < emitters_.size(); ++i)
            if (emitters_[i].isPoint()) {
                chosen[i] = false;
                exact_.push_back(std::uint32_t(i));
            }
    for (Sun& sun : suns_) sun.exact = !chosen[sun.emitter];
    receivers_ = Distribution1D(choiceWeights(power, chosen, parallel));
    if (!usesLightTree(sampling, emitters_.size()) || receivers_.empty()) return;
    std::vector<LightTree::Light> bounds;
    for (std::size_t i = 0; i < emitters_.size(); ++i) {
        if (!chosen[i]) continue;
        treeEmitter_.push_back(std::uint32_t(i));
        const Emitter& e = emitters_[i];
        LightTree::Light& b = bounds.emplace_back();
        // A directional light is its far point (LightSample) in every direction it may come
        // from: the tree weighs it by the irradiance it gives, as a point light's.
        const glm::vec3 p0 =
            e.kind == Kind::Directional ? center_ - e.normal * (radius_ + sunDistance) : e.p0;
        b.lo = glm::min(p0, glm::min(p0 + e.e1, p0 + e.e2));
        b.hi = glm::max(p0, glm::max(p0 + e.e1, p0 + e.e2));
        if (e.kind == Kind::Environment) {  // the whole far sphere
            b.lo = center_ - glm::vec3(radius_ + sunDistance);
            b.hi = center_ + glm::vec3(radius_ + sunDistance);
        }
        b.normal = e.normal;
        b.omni = e.isPoint();
        b.power = treePower[i];
    }
    emitterTree_.assign(emitters_.size(), kNotInTree);
    for (std::size_t t = 0; t < treeEmitter_.size(); ++t)
        emitterTree_[treeEmitter_[t]] = std::uint32_t(t);
    tree_ = LightTree(bounds);
}

float Lights::receiverSelection(glm::vec3 p, glm::vec3 n, std::uint32_t emitter) const {
    if (!choosesPerPoint()) return receivers_.empty() ? 0.0f : receivers_.pdf(emitter);
    const std::uint32_t t = emitterTree_[emitter];
    return t == kNotInTree ? 0.0f : tree_.probability(p, n, t);
}

LightSample Lights::exactLight(std::size_t k, glm::vec2 uPoint) const {
    return pointOn(exact_[k], 1.0f, uPoint);
}

LightSample Lights::sample(float uSelect, glm::vec2 uPoint, float* uRemapped) const {
    if (empty()) return {};
    const std::size_t i = distribution_.sample(uSelect, uRemapped);
    return pointOn(i, distribution_.pdf(i), uPoint);
}

LightSample Lights::sampleForReceivers(float uSelect, glm::vec2 uPoint) const {
    if (receivers_.empty()) return {};
    const std::size_t i = receivers_.sample(uSelect);
    return pointOn(i, receivers_.pdf(i), uPoint);
}

LightSample Lights::sampleAt(glm::vec3 p, glm::vec3 n, float uSelect, glm::vec2 uPoint,
                             LightTree::Memo* memo) const {
    if (!choosesPerPoint()) return sampleForReceivers(uSelect, uPoint);
    std::uint32_t i = 0;
    float selection = 0;
    if (!tree_.sample(p, n, uSelect, i, selection, memo)) return {};
    return pointOn(treeEmitter_[i], selection, uPoint);
}

LightSample Lights::pointOn(std::size_t i, float select, glm::vec2 uPoint) const {
    LightSample s;
    const Emitter& e = emitters_[i];
    s.emitted = e.emitted;
    s.isPoint = e.isPoint();
    s.select = select;
    if (e.kind == Kind::Environment) {
        const EnvironmentMap::Sample sky = environment_->sample(uPoint);
        if (!(sky.pdf > 0)) return s;
        const float distance = radius_ + kSunDistance * radius_;
        s.directional = true;
        s.direction = -sky.toSky;
        s.irradiance = sky.radiance / sky.pdf;
        s.position = center_ + sky.toSky * distance;
        s.normal = s.direction;  // facing the scene
        s.emitted = sky.radiance;
        // Area density on the far sphere whose solid angle from the scene is the sky's.
        s.pdf = select * sky.pdf / (distance * distance);
        return s;
    }
    if (e.kind == Kind::Triangle) {
        const glm::vec2 b = squareToUniformTriangle(uPoint);
        s.position = e.p0 + b.x * e.e1 + b.y * e.e2;
        s.normal = e.normal;
        // Uniform in area with the texel's radiance: the density stays select / area.
        if (e.texture.present()) s.emitted = e.emitted * e.texture.at(b);
        s.pdf = select / e.area;
        return s;
    }
    s.pdf = select;
    s.position = e.p0;
    if (e.kind == Kind::Spot) {
        s.spot = true;
        s.normal = e.normal;
        s.cosOuter = e.cosOuter;
        s.spotScale = e.spotScale;
    } else if (e.kind == Kind::Directional) {
        s.directional = true;
        s.direction = e.normal;
        if (e.oneMinusCos > 0) {
            // Uniform in the disk's cone: cos = 1 - u (1 - cos max), its sine from 1 - cos.
            const float c1 = uPoint.x * e.oneMinusCos;
            const float sine = std::sqrt(std::max(0.0f, c1 * (2.0f - c1)));
            const float phi = 2.0f * kPi * uPoint.y;
            s.direction = glm::normalize(
                Frame(e.normal).toWorld({sine * std::cos(phi), sine * std::sin(phi), 1.0f - c1}));
        }
        s.irradiance = e.emitted * e.sunScale;
        const float distance = radius_ + kSunDistance * radius_;
        s.position = center_ - s.direction * distance;
        s.emitted = s.irradiance * (distance * distance);
        if (e.oneMinusCos > 0) {
            // The disk is seen in the sky (SunDisk), so glossy lobes that find it by BRDF
            // sampling weigh it against this sample: a point of the disk on the far sphere,
            // facing the scene, as the environment's, whose area density there gives the
            // cone's solid-angle density (1 / solid angle) and whose radiance is the disk's.
            const float solidAngle = sunSolidAngle(e.oneMinusCos);
            s.isPoint = false;
            s.normal = s.direction;
            s.emitted = e.emitted * (e.sunScale / solidAngle);
            s.pdf = select / (solidAngle * distance * distance);
        }
    }
    return s;
}

glm::vec3 Lights::sunsSeenByBrdf(glm::vec3 p, glm::vec3 n, glm::vec3 toSky, float brdfPdf,
                                 float lightSamples) const {
    glm::vec3 sum(0.0f);
    for (const Sun& sun : suns_) {
        if (!sun.disk.contains(toSky)) continue;
        // An exact sun has one light sample of its own at p; another one of the receivers'.
        const float samples = sun.exact ? 1.0f : lightSamples;
        const float selection = sun.exact ? 1.0f : receiverSelection(p, n, sun.emitter);
        const float lightPdf = selection / sun.disk.solidAngle();
        sum += sun.disk.radiance * powerHeuristic(brdfPdf, samples * lightPdf);
    }
    return sum;
}

float Lights::environmentPdfAt(glm::vec3 p, glm::vec3 n, glm::vec3 toSky) const {
    if (!environment_) return 0.0f;
    return receiverSelection(p, n, environmentIndex_) * environment_->pdf(toSky);
}

glm::vec3 Lights::diskOrigin(glm::vec3 direction, glm::vec2 u) const {
    const glm::vec2 d = squareToUniformDisk(u);
    // Just outside the sphere, so that nothing in the scene is behind the start.
    return center_ + Frame(direction).toWorld({d.x * radius_, d.y * radius_, -1.001f * radius_});
}

float Lights::diskArea() const {
    return kPi * radius_ * radius_;
}

Lights::ParallelStart Lights::parallelStart(glm::vec3 direction, glm::vec2 u) const {
    const float disk = diskArea();
    if (hasBox_) {
        // The box's eight corners seen along `direction`: their extent on the frame's two
        // axes across it is the rectangle (the frame diskOrigin uses).
        const Frame frame(direction);
        glm::vec2 lo(std::numeric_limits<float>::infinity()), hi(-lo);
        for (int c = 0; c < 8; ++c) {
            const glm::vec3 corner(c & 1 ? boxHi_.x : boxLo_.x, c & 2 ? boxHi_.y : boxLo_.y,
                                   c & 4 ? boxHi_.z : boxLo_.z);
            const glm::vec3 local = frame.toLocal(corner - center_);
            lo = glm::min(lo, glm::vec2(local.x, local.y));
            hi = glm::max(hi, glm::vec2(local.x, local.y));
        }
        const glm::vec2 size = hi - lo;
        const float area = size.x * size.y;
        // A box seen edge-on has no area: its light paths are as few from the disk.
        if (area > 0 && area < disk) {
            const glm::vec2 p = lo + u * size;
            return {center_ + frame.toWorld({p.x, p.y, -1.001f * radius_}), area};
        }
    }
    return {diskOrigin(direction, u), disk};
}

float Lights::areaPdfAt(std::uint32_t mesh, std::uint32_t triangle, glm::vec3 p,
                        glm::vec3 n) const {
    const auto it = triangleToEmitter_.find(triangleKey(mesh, triangle));
    if (it == triangleToEmitter_.end()) return 0;
    return receiverSelection(p, n, it->second) / emitters_[it->second].area;
}

Vpl directLightVpl(const LightSample& s, const TraceableScene& scene, int samples) {
    Vpl v;
    v.omni = s.isPoint;
    v.normal = s.normal;
    v.spot = s.spot;
    v.spotCosOuter = s.cosOuter;
    v.spotScale = s.spotScale;
    v.position = s.isPoint ? s.position : scene.offsetOrigin(s.position, s.normal);
    v.power = s.emitted / (s.pdf * float(samples));
    v.areaPdf = s.isPoint ? 0.0f : s.pdf;
    return v;
}

}  // namespace igi
