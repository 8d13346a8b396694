#include "ShadowSegments.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "math/Warp.h"
#include "sampling/Distribution1D.h"
#include "sampling/Hash.h"

namespace igi {

std::vector<ShadowSegment> randomShadowSegments(const TraceableScene& scene, std::size_t count,
                                                std::uint64_t seed) {
    const auto triangles = scene.triangles();
    std::vector<float> areas;
    for (const auto& t : triangles)
        areas.push_back(0.5f * glm::length(glm::cross(t.p1 - t.p0, t.p2 - t.p0)));
    const Distribution1D byArea(areas);
    SplitMix64 rng(seed);
    auto surfacePoint = [&](glm::vec3& normal) {
        const auto& t = triangles[byArea.sample(rng.uniform())];
        const glm::vec2 b = squareToUniformTriangle({rng.uniform(), rng.uniform()});
        normal = glm::normalize(glm::cross(t.p1 - t.p0, t.p2 - t.p0));
        return t.p0 + b.x * (t.p1 - t.p0) + b.y * (t.p2 - t.p0);
    };
    std::vector<ShadowSegment> segments;
    segments.reserve(count);
    while (segments.size() < count) {
        glm::vec3 na, nb;
        const glm::vec3 a = surfacePoint(na), b = surfacePoint(nb);
        glm::vec3 d = b - a;
        const float length = glm::length(d);
        if (!(length > 0) || !std::isfinite(length)) continue;
        d /= length;
        const glm::vec3 origin = scene.offsetOrigin(a, na, d);
        segments.push_back({origin, d, length * (1.0f - 1e-4f)});
    }
    return segments;
}

}  // namespace igi
