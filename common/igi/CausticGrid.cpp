#include "igi/CausticGrid.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

namespace igi {

CausticGrid::CausticGrid(std::vector<CausticPhoton> photons, float radius)
    : radius_(radius), invCell_(1.0f / (2.0f * radius)), photons_(std::move(photons)) {
    // Each photon is entered under up to 8 cells; about a bucket per entry keeps the lists
    // that distinct cells share short.
    const std::uint32_t size =
        std::bit_ceil(std::max<std::uint32_t>(8u * std::uint32_t(photons_.size()), 8u));
    mask_ = size - 1;
    bucketStart_.assign(size + 1, 0);

    // Counting sort of the entries by bucket, each photon in photon order within a bucket.
    std::vector<std::uint32_t> buckets(8 * photons_.size());
    std::vector<std::uint8_t> counts(photons_.size());
    for (std::size_t i = 0; i < photons_.size(); ++i) {
        counts[i] = std::uint8_t(bucketsHolding(photons_[i].position, &buckets[8 * i]));
        for (int j = 0; j < counts[i]; ++j) ++bucketStart_[buckets[8 * i + j] + 1];
    }
    for (std::uint32_t b = 0; b < size; ++b) bucketStart_[b + 1] += bucketStart_[b];
    entries_.resize(bucketStart_[size]);
    std::vector<std::uint32_t> next(bucketStart_.begin(), bucketStart_.end() - 1);
    for (std::size_t i = 0; i < photons_.size(); ++i)
        for (int j = 0; j < counts[i]; ++j) entries_[next[buckets[8 * i + j]]++] = std::uint32_t(i);
    // Grown by the radius and a margin, so that the test in forEachNear never turns away a point
    // within the radius of a photon (such a point lies within the radius of the box).
    if (photons_.empty()) return;
    lo_ = hi_ = photons_[0].position;
    for (const CausticPhoton& p : photons_) {
        lo_ = glm::min(lo_, p.position);
        hi_ = glm::max(hi_, p.position);
    }
    const glm::vec3 margin =
        glm::vec3(radius * 1.001f) + 1e-6f * glm::max(glm::abs(lo_), glm::abs(hi_));
    lo_ -= margin;
    hi_ += margin;
}

std::uint32_t CausticGrid::hashCell(std::int64_t x, std::int64_t y, std::int64_t z) {
    // Large primes (Teschner et al. 2003); the casts wrap modulo 2^32, which is well defined.
    return (static_cast<std::uint32_t>(x) * 73856093u) ^
           (static_cast<std::uint32_t>(y) * 19349663u) ^
           (static_cast<std::uint32_t>(z) * 83492791u);
}

int CausticGrid::bucketsHolding(glm::vec3 p, std::uint32_t* buckets) const {
    // A query at q reads the block of cells floor(q / cell - 0.5) + {0, 1}^3; the photon's cell
    // c = floor(p / cell) is in that block for the 8 query cells c - {0, 1}^3.
    const glm::dvec3 scaled = glm::dvec3(p) * double(invCell_);
    const std::int64_t cx = floorToInt(scaled.x), cy = floorToInt(scaled.y),
                       cz = floorToInt(scaled.z);
    int count = 0;
    for (int i = 0; i < 8; ++i) {
        const std::uint32_t b = hashCell(cx - (i & 1), cy - ((i >> 1) & 1), cz - (i >> 2)) & mask_;
        if (std::find(buckets, buckets + count, b) == buckets + count) buckets[count++] = b;
    }
    return count;
}

}  // namespace igi
