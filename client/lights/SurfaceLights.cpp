#include "lights/SurfaceLights.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include "sampling/Distribution1D.h"
#include "sampling/Hash.h"
#include "sampling/Sobol.h"

namespace igi {
namespace {

constexpr float kShrink = 0.9f;      // triangles shrunk about their centroid (off edges)
constexpr double kOversample = 1.1;  // the paper's "experimental" 10 %
constexpr float kAligned = 0.5f;     // |cos| between normals of one surface's VSL and photon

struct WorldTriangle {
    glm::vec3 p0, p1, p2;
};

WorldTriangle worldTriangle(const Mesh& mesh, const glm::mat4& m, std::uint32_t t) {
    const glm::uvec3 v = mesh.triangles[t];
    auto at = [&](std::uint32_t i) { return glm::vec3(m * glm::vec4(mesh.positions[i], 1.0f)); };
    return {at(v.x), at(v.y), at(v.z)};
}

bool carriesSurfaceLights(const Material& m) {
    return !m.isEmissive() && !m.isSpecular();
}

float uniform(std::uint64_t seed, std::uint32_t index, std::uint32_t dimension) {
    return Sobol::toFloat(std::uint32_t(hashValues(seed, 0x56534cu, index, dimension) >> 32));
}

// Nearest other live point of i: index and squared distance.
std::pair<std::size_t, float> nearestOther(const std::vector<glm::vec3>& p,
                                           const std::vector<bool>& live, std::size_t i) {
    std::pair<std::size_t, float> best{i, std::numeric_limits<float>::infinity()};
    for (std::size_t j = 0; j < p.size(); ++j) {
        if (j == i || !live[j]) continue;
        const glm::vec3 d = p[j] - p[i];
        const float d2 = glm::dot(d, d);
        if (d2 < best.second) best = {j, d2};
    }
    return best;
}

}  // namespace

std::vector<bool> thinSurfaceLights(const std::vector<glm::vec3>& p, std::size_t count) {
    std::vector<bool> live(p.size(), true);
    std::vector<std::pair<std::size_t, float>> nearest(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) nearest[i] = nearestOther(p, live, i);
    for (std::size_t alive = p.size(); alive > count; --alive) {
        std::size_t worst = p.size();
        for (std::size_t i = 0; i < p.size(); ++i)
            if (live[i] && (worst == p.size() || nearest[i].second < nearest[worst].second))
                worst = i;
        live[worst] = false;
        for (std::size_t i = 0; i < p.size(); ++i)
            if (live[i] && nearest[i].first == worst) nearest[i] = nearestOther(p, live, i);
    }
    return live;
}

std::vector<SurfaceLightSite> placeSurfaceLights(const Scene& scene, const SceneState& state,
                                                 int count, std::uint64_t seed) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> triangles;  // (mesh, triangle)
    std::vector<float> areas;
    for (std::uint32_t i = 0; i < scene.meshes.size(); ++i) {
        const Mesh& mesh = geometryOf(scene, i);
        const glm::mat4 m = meshToWorld(scene, state.transforms, i);
        for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
            if (!carriesSurfaceLights(state.materials[materialOf(scene, i, t)])) continue;
            const WorldTriangle w = worldTriangle(mesh, m, t);
            const float area = 0.5f * glm::length(glm::cross(w.p1 - w.p0, w.p2 - w.p0));
            if (!(area > 0) || !std::isfinite(area)) continue;
            triangles.emplace_back(i, t);
            areas.push_back(area);
        }
    }
    if (triangles.empty() || count <= 0) return {};
    const Distribution1D byArea(areas);
    const auto drawn = std::size_t(std::ceil(double(count) * kOversample));
    std::vector<SurfaceLightSite> sites(drawn);
    for (std::size_t k = 0; k < drawn; ++k) {
        const auto [mesh, triangle] = triangles[byArea.sample(uniform(seed, std::uint32_t(k), 0))];
        // Uniform on the triangle, then pulled toward its centroid.
        float u = uniform(seed, std::uint32_t(k), 1), v = uniform(seed, std::uint32_t(k), 2);
        if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
        const float third = 1.0f / 3.0f;
        sites[k] = {mesh, triangle, third + kShrink * (u - third), third + kShrink * (v - third)};
    }
    const std::vector<SurfaceLight> world = surfaceLightsIn(scene, state, sites);
    std::vector<glm::vec3> positions(world.size());
    for (std::size_t k = 0; k < world.size(); ++k) positions[k] = world[k].position;
    const std::vector<bool> live = thinSurfaceLights(positions, std::size_t(count));
    std::vector<SurfaceLightSite> kept;
    for (std::size_t k = 0; k < sites.size(); ++k)
        if (live[k]) kept.push_back(sites[k]);
    return kept;
}

std::vector<SurfaceLight> surfaceLightsIn(const Scene& scene, const SceneState& state,
                                          const std::vector<SurfaceLightSite>& sites) {
    std::vector<glm::mat4> matrices(scene.meshes.size());
    for (std::size_t i = 0; i < matrices.size(); ++i)
        matrices[i] = meshToWorld(scene, state.transforms, i);
    std::vector<SurfaceLight> out(sites.size());
    for (std::size_t k = 0; k < sites.size(); ++k) {
        const SurfaceLightSite& s = sites[k];
        const WorldTriangle w =
            worldTriangle(geometryOf(scene, s.mesh), matrices[s.mesh], s.triangle);
        out[k].position = (1.0f - s.b1 - s.b2) * w.p0 + s.b1 * w.p1 + s.b2 * w.p2;
        const glm::vec3 n = glm::cross(w.p1 - w.p0, w.p2 - w.p0);
        const float length = glm::length(n);
        out[k].normal = length > 0 ? n / length : glm::vec3(0.0f, 0.0f, 1.0f);
    }
    return out;
}

SurfaceLightHit nearestSurfaceLight(const std::vector<SurfaceLight>& lights, glm::vec3 position,
                                    glm::vec3 normal) {
    std::size_t aligned = lights.size(), any = 0;
    float alignedD2 = std::numeric_limits<float>::infinity(), anyD2 = alignedD2;
    for (std::size_t i = 0; i < lights.size(); ++i) {
        const glm::vec3 d = lights[i].position - position;
        const float d2 = glm::dot(d, d);
        if (d2 < anyD2) anyD2 = d2, any = i;
        if (d2 < alignedD2 && std::fabs(glm::dot(lights[i].normal, normal)) > kAligned)
            alignedD2 = d2, aligned = i;
    }
    const std::size_t i = aligned < lights.size() ? aligned : any;
    return {i, glm::dot(lights[i].normal, normal) >= 0};
}

}  // namespace igi
