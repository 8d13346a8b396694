#include "integrators/RoughGlassLight.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "math/Color.h"
#include "shading/ConnectionBound.h"

namespace igi {
namespace {

// One light sample's light through the rough glass: the path tracer's directLight arithmetic
// with the rough glass's BSDF.
glm::vec3 throughRoughGlass(const TraceableScene& scene, const SurfacePoint& hit,
                            const Lobes& lobes, const LightSample& ls, RoughGlassLights which,
                            RayCounters& counters) {
    if (!(ls.pdf > 0)) return glm::vec3(0.0f);
    if (which == RoughGlassLights::DeltaOnly && !ls.isPoint) return glm::vec3(0.0f);
    const glm::vec3 toLight0 = ls.position - hit.position;
    if (!(glm::dot(toLight0, toLight0) > 0)) return glm::vec3(0.0f);
    const glm::vec3 side =
        glm::dot(toLight0, lobes.faceNormal) >= 0 ? lobes.faceNormal : -lobes.faceNormal;
    const glm::vec3 shadowOrigin = scene.offsetOrigin(hit.position, side);
    const glm::vec3 toLight = ls.position - shadowOrigin;
    const float d2 = glm::dot(toLight, toLight);
    const float d = std::sqrt(d2);
    if (!(d > 0)) return glm::vec3(0.0f);
    const glm::vec3 w = toLight / d;
    const float cosX = std::abs(glm::dot(w, lobes.normal));
    const float cosY = !ls.isPoint ? -glm::dot(w, ls.normal)
                       : ls.spot   ? spotRamp(ls.cosOuter, ls.spotScale, -glm::dot(w, ls.normal))
                                   : 1.0f;
    if (!(cosX > 0) || cosY <= 0 || glm::dot(w, side) <= 0) return glm::vec3(0.0f);
    // Radiance, which refraction scales by eta^2 (a light inside the glass, seen from outside).
    const glm::vec3 f = roughGlassValue(lobes, w) * radianceScale(lobes, w);
    if (isBlack(f)) return glm::vec3(0.0f);
    const glm::vec3 target = ls.isPoint ? ls.position : scene.offsetOrigin(ls.position, ls.normal);
    const float distance = glm::length(target - shadowOrigin);
    if (scene.occluded(shadowOrigin, w, distance * (1.0f - 1e-4f), counters))
        return glm::vec3(0.0f);
    if (ls.isPoint) return f * ls.emitted * (cosX * cosY / (d2 * ls.pdf));
    const float lightPdf = ls.pdf * d2 / cosY;  // solid angle
    const float weight = powerHeuristic(lightPdf, roughGlassPdf(lobes, w));
    return f * ls.emitted * (cosX * weight / lightPdf);
}

}  // namespace

glm::vec3 roughGlassLight(const TraceableScene& scene, const Lights& lights,
                          const SurfacePoint& hit, const Lobes& lobes, float uSelect,
                          glm::vec2 uPoint, RoughGlassLights which, RayCounters& counters) {
    // No normal for the choice: light comes through the surface as well (the light tree would
    // otherwise weigh the lights below it at zero).
    glm::vec3 sum = throughRoughGlass(
        scene, hit, lobes, lights.sampleAt(hit.position, glm::vec3(0.0f), uSelect, uPoint), which,
        counters);
    for (std::size_t k = 0; k < lights.exactLights(); ++k)
        sum += throughRoughGlass(scene, hit, lobes, lights.exactLight(k, uPoint), which, counters);
    return sum;
}

}  // namespace igi
