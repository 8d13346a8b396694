#include "lighting/CacheSites.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include "sampling/Hash.h"
#include "sampling/Sobol.h"
#include "scene/SceneBounds.h"

namespace igi {
namespace {

constexpr std::uint64_t kSiteStream = 0x43414348u;  // "CACH"

struct Corners {
    glm::vec3 p0, p1, p2;
};

Corners cornersOf(const Mesh& mesh, const glm::mat4& m, std::uint32_t t) {
    const glm::uvec3 v = mesh.triangles[t];
    auto at = [&](std::uint32_t i) { return glm::vec3(m * glm::vec4(mesh.positions[i], 1.0f)); };
    return {at(v.x), at(v.y), at(v.z)};
}

bool carriesSites(const Material& m) {
    return !m.isSpecular();
}

float areaOf(const Corners& c) {
    return 0.5f * glm::length(glm::cross(c.p1 - c.p0, c.p2 - c.p0));
}

// Calls f(mesh, triangle, area) for every triangle that carries sites and has an area.
template <typename F>
void forEachSiteTriangle(const Scene& scene, const SceneState& state, F&& f) {
    for (std::uint32_t i = 0; i < scene.meshes.size(); ++i) {
        const Mesh& mesh = geometryOf(scene, i);
        const glm::mat4 m = meshToWorld(scene, state.transforms, i);
        for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
            if (!carriesSites(state.materials[materialOf(scene, i, t)])) continue;
            const float a = areaOf(cornersOf(mesh, m, t));
            if (a > 0 && std::isfinite(a)) f(i, t, a);
        }
    }
}

double totalArea(const Scene& scene, const SceneState& state) {
    double total = 0;
    forEachSiteTriangle(scene, state, [&](std::uint32_t, std::uint32_t, float a) { total += a; });
    return total;
}

}  // namespace

CacheSites CacheSites::forScene(const Scene& scene, const RenderSettings& settings) {
    return place(scene, settings.cacheSpacing * worldBounds(scene).diagonal(), settings.seed,
                 kMaxSites);
}

CacheSites CacheSites::place(const Scene& scene, float spacing, std::uint64_t seed,
                             std::size_t maxSites) {
    CacheSites out;
    const SceneState state = SceneState::of(scene);
    const double area = totalArea(scene, state);
    out.area = area;
    if (!(spacing > 0) || !(area > 0) || maxSites == 0) return out;
    double h2 = double(spacing) * double(spacing);
    if (area / h2 > double(maxSites)) h2 = area / double(maxSites);
    out.spacing = float(std::sqrt(h2));
    forEachSiteTriangle(scene, state, [&](std::uint32_t i, std::uint32_t t, float a) {
        const double expected = double(a) / h2;
        const std::uint64_t h = hashValues(seed, kSiteStream, i, t);
        const double fraction = expected - std::floor(expected);
        auto count = std::uint32_t(std::floor(expected));
        if (Sobol::toFloat(std::uint32_t(h >> 32)) < fraction) ++count;
        const auto s0 = std::uint32_t(h), s1 = std::uint32_t(mix64(h) >> 32);
        for (std::uint32_t j = 0; j < count && out.sites.size() < maxSites; ++j) {
            // Uniform on the triangle by the square root warp, which keeps the points'
            // stratification.
            const float su = std::sqrt(Sobol::scrambled(j, 0, s0));
            const float v = Sobol::scrambled(j, 1, s1);
            out.sites.push_back({i, t, su * (1.0f - v), su * v});
        }
    });
    return out;
}

SiteGrid::SiteGrid(const Scene& scene, const SceneState& state, const CacheSites& sites,
                   float radius)
    : radius_(radius), invCell_(1.0f / radius) {
    const std::vector<SurfaceLight> world = surfaceLightsIn(scene, state, sites.sites);
    positions_.resize(world.size());
    normals_.resize(world.size());
    for (std::size_t k = 0; k < world.size(); ++k) {
        positions_[k] = world[k].position;
        normals_[k] = world[k].normal;
    }
    const std::uint32_t size =
        std::bit_ceil(std::max<std::uint32_t>(2u * std::uint32_t(world.size()), 8u));
    mask_ = size - 1;
    bucketStart_.assign(size + 1, 0);
    std::vector<std::uint32_t> bucket(world.size());
    for (std::size_t k = 0; k < world.size(); ++k) {
        const glm::vec3 p = positions_[k];
        bucket[k] = hashCell(std::int64_t(std::floor(double(p.x) * double(invCell_))),
                             std::int64_t(std::floor(double(p.y) * double(invCell_))),
                             std::int64_t(std::floor(double(p.z) * double(invCell_)))) &
                    mask_;
        ++bucketStart_[bucket[k] + 1];
    }
    for (std::uint32_t b = 0; b < size; ++b) bucketStart_[b + 1] += bucketStart_[b];
    sorted_.resize(world.size());
    std::vector<std::uint32_t> next(bucketStart_.begin(), bucketStart_.end() - 1);
    for (std::size_t k = 0; k < world.size(); ++k) sorted_[next[bucket[k]]++] = std::uint32_t(k);
}

std::uint32_t SiteGrid::hashCell(std::int64_t x, std::int64_t y, std::int64_t z) {
    return (static_cast<std::uint32_t>(x) * 73856093u) ^
           (static_cast<std::uint32_t>(y) * 19349663u) ^
           (static_cast<std::uint32_t>(z) * 83492791u);
}

void interpolationWeights(const SiteGrid& grid, glm::vec3 p, glm::vec3 n, float maxAngleCos,
                          SiteWeights& out) {
    out.count = 0;
    const float a = grid.radius();
    const float invA = 1.0f / a;
    const float invAngle = 1.0f / std::sqrt(std::max(1e-6f, 1.0f - maxAngleCos));
    grid.forEachNear(p, [&](std::uint32_t site) {
        glm::vec3 nk = grid.normal(site);
        std::uint32_t side = 0;
        if (glm::dot(nk, n) < 0) nk = -nk, side = 1;
        const float c = glm::dot(nk, n);
        if (c < maxAngleCos) return;
        const glm::vec3 d = p - grid.position(site);
        if (std::fabs(glm::dot(d, nk)) > 0.25f * a) return;
        const float e = glm::length(d) * invA + std::sqrt(std::max(0.0f, 1.0f - c)) * invAngle;
        if (!(e < 1.0f) || out.count == SiteWeights::kMaxWeights) return;
        out.items[out.count++] = {2 * site + side, 1.0f / std::max(e, 1e-3f) - 1.0f};
    });
    std::sort(out.items, out.items + out.count,
              [](const SiteWeight& x, const SiteWeight& y) { return x.record < y.record; });
}

}  // namespace igi
