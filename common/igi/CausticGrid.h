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
/// starting at b = floor(p / cell - 0.5). Each bucket holds the photons of a query cell's whole
/// 2 x 2 x 2 block (a photon is entered under the 8 cells whose block holds its own cell), so a
/// query reads one contiguous list: one lookup and one loop, rather than eight of each whose
/// lengths (0-3 photons) the branch predictor cannot guess. They were a tenth of an accumulated
/// frame in the default scene. Only occupied cells cost memory: cell coordinates are hashed
/// (unsigned arithmetic, so overflow is defined) into a table of buckets. Distinct cells may
/// share a bucket, so every candidate's distance is checked, and a photon entered under two cells
/// of one bucket is entered once. A bucket lists photon indices: the table and the lists take
/// up to 64 bytes per photon beside its own 48.
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
    /// std::floor, without a call into libm (the portable build has no SSE4.1 rounding
    /// instruction); exact for |x| < 2^62.
    static std::int64_t floorToInt(double x) {
        const auto i = std::int64_t(x);
        return double(i) > x ? i - 1 : i;
    }
    /// Writes the distinct buckets (at most 8) of the query cells whose block holds the photon
    /// at p; returns how many it wrote.
    int bucketsHolding(glm::vec3 p, std::uint32_t* buckets) const;

    float radius_ = 0;
    float invCell_ = 0;
    glm::vec3 lo_{0.0f}, hi_{0.0f};  ///< the photons' bounds, grown by the radius
    std::uint32_t mask_ = 0;
    std::vector<CausticPhoton> photons_;      ///< as given
    std::vector<std::uint32_t> entries_;      ///< photon indices, sorted by bucket
    std::vector<std::uint32_t> bucketStart_;  ///< mask_ + 2 entries
};

template <typename F>
void CausticGrid::forEachNear(glm::vec3 p, F&& f) const {
    if (photons_.empty()) return;
    // Most points see no caustic at all: one box test spares them the lookup.
    if (p.x < lo_.x || p.y < lo_.y || p.z < lo_.z || p.x > hi_.x || p.y > hi_.y || p.z > hi_.z)
        return;
    const float r2 = radius_ * radius_;
    const glm::dvec3 scaled = glm::dvec3(p) * double(invCell_) - 0.5;
    const std::uint32_t bucket =
        hashCell(floorToInt(scaled.x), floorToInt(scaled.y), floorToInt(scaled.z)) & mask_;
    const std::uint32_t end = bucketStart_[bucket + 1];
    for (std::uint32_t k = bucketStart_[bucket]; k < end; ++k) {
        const CausticPhoton& ph = photons_[entries_[k]];
        const glm::vec3 d = ph.position - p;
        if (d.x * d.x + d.y * d.y + d.z * d.z <= r2) f(ph);
    }
}

}  // namespace igi
