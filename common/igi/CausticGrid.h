#pragma once

#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/gtc/type_precision.hpp>
#include <glm/vec3.hpp>

#include "igi/CausticPhoton.h"

namespace igi {

/// Caustic photons in a hashed uniform grid for fixed-radius queries (paper, section 4.1).
///
/// Cells are 2r wide, so the ball of radius r around a query point lies in the 2 x 2 x 2 cells
/// starting at floor(p / cell - 0.5): exactly 8 lookups. Only occupied cells cost memory: cell
/// coordinates are hashed (unsigned arithmetic, so overflow is defined) into a table of buckets,
/// and photons are stored sorted by bucket. Distinct cells may share a bucket, so every candidate's
/// distance is checked, and a bucket reached from two of the 8 cells is visited once.
class CausticGrid {
  public:
    CausticGrid() = default;
    CausticGrid(std::vector<CausticPhoton> photons, float radius);

    float radius() const { return radius_; }
    std::span<const CausticPhoton> photons() const { return photons_; }

    /// Calls f(photon) for every photon within `radius` of p (distance <= radius).
    template <typename F>
    void forEachNear(glm::vec3 p, F&& f) const;

  private:
    static std::uint32_t hashCell(std::int64_t x, std::int64_t y, std::int64_t z);
    std::uint32_t bucketOf(glm::vec3 p) const;

    float radius_ = 0;
    float invCell_ = 0;
    glm::vec3 lo_{0.0f}, hi_{0.0f};  ///< the photons' bounds, grown by the radius
    std::uint32_t mask_ = 0;
    std::vector<CausticPhoton> photons_;      ///< sorted by bucket
    std::vector<std::uint32_t> bucketStart_;  ///< mask_ + 2 entries
};

template <typename F>
void CausticGrid::forEachNear(glm::vec3 p, F&& f) const {
    if (photons_.empty()) return;
    // Most points see no caustic at all: one box test spares them the eight lookups.
    if (p.x < lo_.x || p.y < lo_.y || p.z < lo_.z || p.x > hi_.x || p.y > hi_.y || p.z > hi_.z)
        return;
    const float r2 = radius_ * radius_;
    const glm::dvec3 scaled = glm::dvec3(p) * double(invCell_) - 0.5;
    const std::int64_t bx = std::int64_t(std::floor(scaled.x));
    const std::int64_t by = std::int64_t(std::floor(scaled.y));
    const std::int64_t bz = std::int64_t(std::floor(scaled.z));
    std::uint32_t visited[8];
    int visitedCount = 0;
    for (int i = 0; i < 8; ++i) {
        const std::uint32_t bucket =
            hashCell(bx + (i & 1), by + ((i >> 1) & 1), bz + (i >> 2)) & mask_;
        bool seen = false;
        for (int j = 0; j < visitedCount; ++j) seen |= visited[j] == bucket;
        if (seen) continue;
        visited[visitedCount++] = bucket;
        for (std::uint32_t k = bucketStart_[bucket]; k < bucketStart_[bucket + 1]; ++k) {
            const glm::vec3 d = photons_[k].position - p;
            if (d.x * d.x + d.y * d.y + d.z * d.z <= r2) f(photons_[k]);
        }
    }
}

}  // namespace igi
