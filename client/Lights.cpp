#include "Lights.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "math/Color.h"
#include "math/Warp.h"

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

}  // namespace

Lights::Lights(const TraceableScene& traceable, const std::vector<PointLight>& pointLights,
               LightSampling sampling) {
    std::vector<float> power;
    // A face listed twice (duplicated in its file) is one surface, seen once: it must be one
    // light, or sampling it would count its light twice. The copy maps to the same emitter so that
    // a path that hits the copy finds the density of the light it is.
    std::map<Corners, std::uint32_t> emitterAt;
    for (const auto& t : traceable.emissiveTriangles()) {
        Emitter e;
        e.p0 = t.p0;
        e.e1 = t.p1 - t.p0;
        e.e2 = t.p2 - t.p0;
        const glm::vec3 c = glm::cross(e.e1, e.e2);
        const float len = glm::length(c);
        if (!(len > 0) || !std::isfinite(len)) continue;  // a degenerate triangle emits nothing
        const auto [it, fresh] =
            emitterAt.try_emplace(cornersOf(t), std::uint32_t(emitters_.size()));
        if (!fresh) {
            triangleToEmitter_[triangleKey(t.mesh, t.triangle)] = it->second;
            continue;
        }
        e.normal = c / len;
        e.area = 0.5f * len;
        e.emitted = traceable.materials()[t.material].emission;
        triangleToEmitter_[triangleKey(t.mesh, t.triangle)] = std::uint32_t(emitters_.size());
        emitters_.push_back(e);
        power.push_back(kPi * e.area * luminance(e.emitted));  // one-sided Lambertian emitter
    }
    for (const PointLight& p : pointLights) {
        if (!p.on) continue;
        Emitter e;
        e.p0 = p.position;
        e.emitted = p.intensity;
        e.isPoint = true;
        emitters_.push_back(e);
        power.push_back(4.0f * kPi * luminance(p.intensity));
    }
    distribution_ = Distribution1D(power);
    if (!usesLightTree(sampling, emitters_.size()) || distribution_.empty()) return;
    std::vector<LightTree::Light> bounds(emitters_.size());
    for (std::size_t i = 0; i < emitters_.size(); ++i) {
        const Emitter& e = emitters_[i];
        LightTree::Light& b = bounds[i];
        b.lo = glm::min(e.p0, glm::min(e.p0 + e.e1, e.p0 + e.e2));
        b.hi = glm::max(e.p0, glm::max(e.p0 + e.e1, e.p0 + e.e2));
        b.normal = e.normal;
        b.omni = e.isPoint;
        b.power = power[i];
    }
    tree_ = LightTree(bounds);
}

LightSample Lights::sample(float uSelect, glm::vec2 uPoint, float* uRemapped) const {
    if (empty()) return {};
    const std::size_t i = distribution_.sample(uSelect, uRemapped);
    return pointOn(i, distribution_.pdf(i), uPoint);
}

LightSample Lights::sampleAt(glm::vec3 p, glm::vec3 n, float uSelect, glm::vec2 uPoint,
                             LightTree::Memo* memo) const {
    if (!choosesPerPoint()) return sample(uSelect, uPoint);
    std::uint32_t i = 0;
    float selection = 0;
    if (!tree_.sample(p, n, uSelect, i, selection, memo)) return {};
    return pointOn(i, selection, uPoint);
}

LightSample Lights::pointOn(std::size_t i, float select, glm::vec2 uPoint) const {
    LightSample s;
    const Emitter& e = emitters_[i];
    s.emitted = e.emitted;
    s.isPoint = e.isPoint;
    if (e.isPoint) {
        s.position = e.p0;
        s.pdf = select;
        return s;
    }
    const glm::vec2 b = squareToUniformTriangle(uPoint);
    s.position = e.p0 + b.x * e.e1 + b.y * e.e2;
    s.normal = e.normal;
    s.pdf = select / e.area;
    return s;
}

float Lights::areaPdfAt(std::uint32_t mesh, std::uint32_t triangle, glm::vec3 p,
                        glm::vec3 n) const {
    const auto it = triangleToEmitter_.find(triangleKey(mesh, triangle));
    if (it == triangleToEmitter_.end()) return 0;
    const float selection =
        choosesPerPoint() ? tree_.probability(p, n, it->second) : distribution_.pdf(it->second);
    return selection / emitters_[it->second].area;
}

Vpl directLightVpl(const LightSample& s, const TraceableScene& scene, int samples) {
    Vpl v;
    v.omni = s.isPoint;
    v.normal = s.normal;
    v.position = s.isPoint ? s.position : scene.offsetOrigin(s.position, s.normal);
    v.power = s.emitted / (s.pdf * float(samples));
    v.areaPdf = s.isPoint ? 0.0f : s.pdf;
    return v;
}

}  // namespace igi
