#include "lighting/CausticShooter.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include <glm/geometric.hpp>

#include "math/Color.h"
#include "math/Frame.h"
#include "math/Warp.h"
#include "sampling/LightPathSampler.h"
#include "shading/Scattering.h"

namespace igi {
namespace {

// Directions toward a target: a cone around it, or every direction from inside its sphere.
bool insideSphere(glm::vec3 origin, glm::vec3 center, float radius) {
    return glm::length(center - origin) <= radius;
}

// The cone of directions from a point outside a target's sphere that holds the sphere. Its width
// is kept as 1 - cos(half-angle), computed from the sine in double: as 1 - sqrt(1 - sin^2) in
// float it loses every digit for a target that looks small from the light (it is exactly 0, a
// cone of no width with an infinite density, below sin = 2.4e-4, and several per cent off at
// sin = 1e-3), which gave the caustic photons of small or distant mirrors and glass a wrong
// power, or none.
struct Cone {
    glm::dvec3 axis{0.0};
    double sin2 = 0;         ///< sin^2 of the half-angle
    double oneMinusCos = 0;  ///< 1 - cos of the half-angle, in (0, 1)
};

Cone coneAround(glm::vec3 origin, glm::vec3 center, float radius) {
    const glm::dvec3 toCenter = glm::dvec3(center) - glm::dvec3(origin);
    const double d2 = glm::dot(toCenter, toCenter);
    Cone cone;
    cone.axis = toCenter / std::sqrt(d2);
    cone.sin2 = std::min(1.0, double(radius) * double(radius) / d2);
    cone.oneMinusCos = cone.sin2 / (1.0 + std::sqrt(1.0 - cone.sin2));
    return cone;
}

// Whether `direction` lies in the cone, by its sine (well conditioned for a narrow cone, where
// comparing cosines near 1 is not).
bool inCone(const Cone& cone, glm::vec3 direction) {
    const glm::dvec3 w = glm::normalize(glm::dvec3(direction));
    if (glm::dot(w, cone.axis) <= 0) return false;
    const glm::dvec3 c = glm::cross(w, cone.axis);
    return glm::dot(c, c) <= cone.sin2;
}

// A uniform direction in the cone (density 1 / (2 pi (1 - cos))), with its sine computed from
// 1 - cos directly for the same reason.
glm::vec3 sampleCone(const Cone& cone, glm::vec2 u) {
    const double h = double(u.x) * cone.oneMinusCos;  // 1 - cos(theta)
    const double sinTheta = std::sqrt(std::max(0.0, h * (2.0 - h)));
    const double phi = 2.0 * double(kPi) * double(u.y);
    const glm::vec3 local(float(sinTheta * std::cos(phi)), float(sinTheta * std::sin(phi)),
                          float(1.0 - h));
    return Frame(glm::vec3(cone.axis)).toWorld(local);
}

}  // namespace

CausticShooter::CausticShooter(const TraceableScene& scene, const Lights& lights,
                               const RenderSettings& settings)
    : scene_(scene),
      lights_(lights),
      seed_(settings.seed),
      photons_(std::uint32_t(std::max(0, settings.causticPhotons))),
      maxDepth_(std::uint32_t(std::max(1, settings.maxEyeDepth))),
      radius_(settings.causticRadius * scene.diagonal()) {
    // One target per specular object: the triangles of one mesh with one specular material.
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::pair<glm::vec3, glm::vec3>> boxes;
    for (const auto& t : scene.specularTriangles()) {
        auto [it, fresh] = boxes.try_emplace({t.mesh, t.material}, t.p0, t.p0);
        for (glm::vec3 p : {t.p0, t.p1, t.p2}) {
            it->second.first = glm::min(it->second.first, p);
            it->second.second = glm::max(it->second.second, p);
        }
    }
    for (const auto& [key, box] : boxes) {
        const glm::vec3 center = 0.5f * (box.first + box.second);
        // A little larger than the box's half diagonal so rays grazing its rim are not lost.
        const float radius =
            0.5f * glm::length(box.second - box.first) * 1.001f + 1e-6f * scene.diagonal();
        targets_.push_back({center, radius});
    }
}

float CausticShooter::directionPdf(glm::vec3 origin, glm::vec3 direction) const {
    double pdf = 0;
    for (const Target& t : targets_) {
        if (insideSphere(origin, t.center, t.radius)) {
            pdf += 1.0 / (4.0 * double(kPi));
            continue;
        }
        const Cone cone = coneAround(origin, t.center, t.radius);
        if (inCone(cone, direction)) pdf += 1.0 / (2.0 * double(kPi) * cone.oneMinusCos);
    }
    return float(pdf / double(targets_.size()));
}

bool CausticShooter::samplePhotonDirection(glm::vec3 origin, float uTarget, glm::vec2 u,
                                           glm::vec3& direction, float& pdf) const {
    const auto index =
        std::min<std::size_t>(std::size_t(uTarget * targets_.size()), targets_.size() - 1);
    const Target& t = targets_[index];
    if (insideSphere(origin, t.center, t.radius)) {
        direction = squareToUniformSphere(u);
    } else {
        direction = sampleCone(coneAround(origin, t.center, t.radius), u);
    }
    // The same direction could have come from another target's cone: use the mixture density.
    pdf = directionPdf(origin, direction);
    return pdf > 0;
}

bool CausticShooter::sampleParallelOrigin(glm::vec3 direction, float uTarget, glm::vec2 u,
                                          glm::vec3& origin, float& pdf) const {
    const auto index =
        std::min<std::size_t>(std::size_t(uTarget * targets_.size()), targets_.size() - 1);
    const Target& t = targets_[index];
    const Frame frame(direction);
    const glm::vec2 d = squareToUniformDisk(u) * t.radius;
    // Back along the light to the plane just outside the scene's bounding sphere.
    const float back =
        glm::dot(t.center - scene_.center(), direction) + 0.5005f * scene_.diagonal();
    origin = t.center + frame.toWorld({d.x, d.y, -back});
    double density = 0;
    for (const Target& other : targets_) {
        const glm::vec3 offset = origin - other.center;
        const float along = glm::dot(offset, direction);
        const glm::vec3 across = offset - along * direction;
        if (glm::dot(across, across) <= other.radius * other.radius)
            density += 1.0 / (double(kPi) * double(other.radius) * double(other.radius));
    }
    pdf = float(density / double(targets_.size()));
    return pdf > 0;
}

std::vector<CausticPhoton> CausticShooter::shoot(std::uint32_t frame, std::uint32_t setIndex,
                                                 std::uint32_t& shot, RayCounters& counters) const {
    std::vector<CausticPhoton> photons;
    shot = 0;
    if (!active()) return photons;
    const LightPathSampler sampler(seed_, frame, SampleStream::CausticPhotons, setIndex, photons_,
                                   maxDepth_ + 1);
    for (std::uint32_t j = 0; j < photons_; ++j) {
        ++shot;
        float uTarget = 0;
        const LightSample light = lights_.sample(
            sampler.emission(j, 0), {sampler.emission(j, 1), sampler.emission(j, 2)}, &uTarget);
        if (light.directional) {
            // Parallel light: aimed by where it starts, on the targets' shadows.
            glm::vec3 origin;
            float pdfArea = 0;
            if (!sampleParallelOrigin(light.direction, uTarget,
                                      {sampler.emission(j, 3), sampler.emission(j, 4)}, origin,
                                      pdfArea))
                continue;
            const glm::vec3 power = light.irradiance / (light.select * pdfArea * float(photons_));
            trace(origin, light.direction, power, j, sampler, photons, counters);
            continue;
        }
        glm::vec3 direction;
        float pdfDirection = 0;
        if (!samplePhotonDirection(light.position, uTarget,
                                   {sampler.emission(j, 3), sampler.emission(j, 4)}, direction,
                                   pdfDirection))
            continue;
        glm::vec3 power;
        glm::vec3 origin = light.position;
        if (light.isPoint) {
            const float ramp = light.spot ? spotRamp(light.cosOuter, light.spotScale,
                                                     glm::dot(direction, light.normal))
                                          : 1.0f;
            if (!(ramp > 0)) continue;
            power = light.emitted * ramp / (light.pdf * pdfDirection * float(photons_));
        } else {
            const float cosLight = glm::dot(direction, light.normal);
            if (cosLight <= 0) continue;  // area lights emit on their front side only
            power = light.emitted * cosLight / (light.pdf * pdfDirection * float(photons_));
            origin = scene_.offsetOrigin(light.position, light.normal);
        }
        trace(origin, direction, power, j, sampler, photons, counters);
    }
    return photons;
}

void CausticShooter::shootFromVpls(std::uint32_t frame, std::uint32_t setIndex,
                                   const std::vector<Vpl>& vpls, std::uint32_t count,
                                   std::vector<CausticPhoton>& out, std::uint32_t& shot,
                                   RayCounters& counters) const {
    if (targets_.empty() || vpls.empty() || count == 0) return;
    const LightPathSampler sampler(seed_, frame, SampleStream::IndirectCausticPhotons, setIndex,
                                   count, maxDepth_ + 1);
    const float vplCount = float(vpls.size());
    for (std::uint32_t j = 0; j < count; ++j) {
        ++shot;
        // One number picks the VPL and, rescaled, the target.
        const float u = sampler.emission(j, 0) * vplCount;
        const auto index = std::min<std::size_t>(std::size_t(u), vpls.size() - 1);
        const Vpl& v = vpls[index];
        const float uTarget = std::min(u - float(index), 0.99999994f);
        glm::vec3 direction;
        float pdfDirection = 0;
        if (!samplePhotonDirection(v.position, uTarget,
                                   {sampler.emission(j, 3), sampler.emission(j, 4)}, direction,
                                   pdfDirection))
            continue;
        const float cosY = glm::dot(direction, v.normalToward(-direction));
        if (cosY <= 0) continue;
        glm::vec3 intensity = v.power;
        if (v.glossy()) intensity += glossyIntensity(v, direction);
        const glm::vec3 power = intensity * (cosY * vplCount / (pdfDirection * float(count)));
        trace(v.position, direction, power, j, sampler, out, counters);
    }
}

void CausticShooter::trace(glm::vec3 origin, glm::vec3 direction, glm::vec3 power,
                           std::uint32_t path, const LightPathSampler& sampler,
                           std::vector<CausticPhoton>& out, RayCounters& counters) const {
    SurfacePoint hit;
    for (std::uint32_t bounce = 1; bounce <= maxDepth_ + 1; ++bounce) {
        if (!scene_.intersect(origin, direction, std::numeric_limits<float>::infinity(), hit,
                              counters))
            return;
        const Lobes lobes = lobesAt(hit, -direction);
        // A non-delta surface reached through mirrors and glass stores the photon (L S+ D: a
        // caustic); what it reflects from there on is the VPLs' business.
        if (bounce > 1 && lobes.hasNonDelta())
            out.push_back({hit.position, direction, power, lobes.faceNormal});
        // Only delta continuations make caustics.
        Lobe lobe;
        float probability = 0;
        if (bounce > maxDepth_) return;
        const float uLobe = sampler.bounce(path, bounce, 2);
        if (!chooseDeltaLobe(lobes, uLobe, lobe, probability)) return;
        glm::vec3 weight;
        if (!sampleLobe(lobes, lobe,
                        {sampler.bounce(path, bounce, 0), sampler.bounce(path, bounce, 1)},
                        remapChoice(uLobe, probability), direction, weight))
            return;
        power *= weight / probability;
        if (isBlack(power)) return;
        origin = scene_.offsetOrigin(hit.position, lobes.faceNormal, direction);
    }
}

}  // namespace igi
