#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "lights/SurfaceLights.h"
#include "render/RenderSettings.h"
#include "scene/Scene.h"
#include "scene/SceneState.h"

namespace igi {

/// Where cached lighting is kept: instant caching's records (paper 003) and the photon map's
/// texels (paper 002). A site is a point of one triangle in barycentric coordinates, so it moves
/// with its object, and each site has two sides (a thin wall is lit from both).
///
/// Placement is a function of the scene as loaded, the spacing and the seed only, so every
/// client has the same sites and a record's position never depends on which pixels asked for
/// it (the paper creates records where a pixel first finds none, which on a cluster would make
/// the image depend on which client rendered what; docs/MODES.md). Each triangle of a surface
/// that reflects diffusely or glossily gets area / spacing^2 sites on average: the integer part
/// always, one more with the probability of the fraction, at the first points of a scrambled
/// Sobol' sequence warped onto the triangle, so that large triangles are covered evenly and
/// finely tessellated meshes get sites at the same density without one per triangle.
struct CacheSites {
    std::vector<SurfaceLightSite> sites;
    float spacing = 0;  ///< world units, in the scene as loaded
    double area = 0;    ///< of the surfaces that carry sites, in the scene as loaded

    /// At most `maxSites` sites: a scene whose area asks for more gets a wider spacing.
    static CacheSites place(const Scene& scene, float spacing, std::uint64_t seed,
                            std::size_t maxSites);
    /// The sites of the cache modes (render.cache_spacing: a fraction of the loaded scene's
    /// diagonal), at most kMaxSites.
    static CacheSites forScene(const Scene& scene, const RenderSettings& settings);
    static constexpr std::size_t kMaxSites = std::size_t(1) << 18;
};

/// The sites of one scene state, in world space, in a hashed grid for queries within a fixed
/// radius: cells as wide as the radius, the 27 around the query's own visited (fewer
/// candidates than CausticGrid's 8 cells of twice the radius: sites lie on surfaces, and a
/// surface crosses few of the small cells).
class SiteGrid {
  public:
    SiteGrid() = default;
    SiteGrid(const Scene& scene, const SceneState& state, const CacheSites& sites, float radius);

    float radius() const { return radius_; }
    std::size_t size() const { return positions_.size(); }
    glm::vec3 position(std::uint32_t site) const { return positions_[site]; }
    /// The unit geometric normal of the site's front side.
    glm::vec3 normal(std::uint32_t site) const { return normals_[site]; }

    /// Calls f(site) for every site within `radius` of p.
    template <typename F>
    void forEachNear(glm::vec3 p, F&& f) const;

  private:
    static std::uint32_t hashCell(std::int64_t x, std::int64_t y, std::int64_t z);

    float radius_ = 0;
    float invCell_ = 0;
    std::uint32_t mask_ = 0;
    std::vector<glm::vec3> positions_, normals_;
    std::vector<std::uint32_t> sorted_;       ///< site indices by bucket
    std::vector<std::uint32_t> bucketStart_;  ///< mask_ + 2 entries
};

/// One site's side and its weight in an interpolation (no initializers: SiteWeights holds an
/// array of them on the stack of every query).
struct SiteWeight {
    std::uint32_t record;  ///< 2 site + (0: front side, 1: back side)
    float weight;
};

/// The records an interpolation at point p with unit normal n (on the viewer's side) uses, with
/// their weights (docs/MODES.md, "Instant caching"): the side of each site within the grid's
/// radius a that faces n's way, if its normal is within `maxAngleCos` of n and p lies near its
/// tangent plane (|(p - x_k) . n_k| <= a / 4: not the floor under a table top). The paper's
/// error e_k = |p - x_k| / a + sqrt(1 - n . n_k) / sqrt(1 - maxAngleCos) (its equation 5, each
/// term scaled to reach 1 at the limit, so that it means the same at every scale) gives the
/// weight 1 / e_k - 1, which falls to 0 at the limit, so a site leaving the neighbourhood as p
/// moves leaves no seam. None when no site qualifies. Sorted by record, so that any sum over
/// them is done in the same order by every client; at most kMaxWeights (the first found, in
/// the grid's order, which is the same on every client).
struct SiteWeights {
    static constexpr int kMaxWeights = 96;
    SiteWeight items[kMaxWeights];
    int count = 0;
    bool empty() const { return count == 0; }
    const SiteWeight* begin() const { return items; }
    const SiteWeight* end() const { return items + count; }
};
/// The cache modes' maxAngleCos: normals farther apart than about 25 degrees are not
/// interpolated.
constexpr float kInterpolationMaxAngleCos = 0.9f;
void interpolationWeights(const SiteGrid& grid, glm::vec3 p, glm::vec3 n, float maxAngleCos,
                          SiteWeights& out);

/// The weighted mean of record(r) over the records an interpolation at (p, n) uses, or
/// fallback() where none qualifies; summed in the records' order.
template <typename Record, typename Fallback>
glm::vec3 interpolate(const SiteGrid& grid, glm::vec3 p, glm::vec3 n, float maxAngleCos,
                      Record&& record, Fallback&& fallback) {
    SiteWeights weights;
    interpolationWeights(grid, p, n, maxAngleCos, weights);
    if (weights.empty()) return fallback();
    glm::vec3 sum(0.0f);
    float total = 0;
    for (const SiteWeight& w : weights) {
        sum += w.weight * record(w.record);
        total += w.weight;
    }
    return sum / total;
}

template <typename F>
void SiteGrid::forEachNear(glm::vec3 p, F&& f) const {
    if (positions_.empty()) return;
    const float r2 = radius_ * radius_;
    const auto bx = std::int64_t(std::floor(double(p.x) * double(invCell_))) - 1;
    const auto by = std::int64_t(std::floor(double(p.y) * double(invCell_))) - 1;
    const auto bz = std::int64_t(std::floor(double(p.z) * double(invCell_))) - 1;
    std::uint32_t visited[27];
    int visitedCount = 0;
    for (int i = 0; i < 27; ++i) {
        const std::uint32_t bucket = hashCell(bx + i % 3, by + (i / 3) % 3, bz + i / 9) & mask_;
        bool seen = false;
        for (int j = 0; j < visitedCount; ++j) seen |= visited[j] == bucket;
        if (seen) continue;
        visited[visitedCount++] = bucket;
        for (std::uint32_t k = bucketStart_[bucket]; k < bucketStart_[bucket + 1]; ++k) {
            const std::uint32_t site = sorted_[k];
            const glm::vec3 d = positions_[site] - p;
            if (d.x * d.x + d.y * d.y + d.z * d.z <= r2) f(site);
        }
    }
}

}  // namespace igi
