#include "igi/CausticGrid.h"

#include <bit>
#include <cmath>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

namespace igi {

CausticGrid::CausticGrid(std::vector<CausticPhoton> photons, float radius)
    : radius_(radius), invCell_(1.0f / (2.0f * radius)) {
    // A table with about two buckets per photon keeps chains short.
    const std::uint32_t size = std::bit_ceil(std::max<std::uint32_t>(2u * photons.size(), 8u));
    mask_ = size - 1;
    bucketStart_.assign(size + 1, 0);

    // Counting sort of the photons by bucket.
    std::vector<std::uint32_t> bucket(photons.size());
    for (std::size_t i = 0; i < photons.size(); ++i) {
        bucket[i] = bucketOf(photons[i].position);
        ++bucketStart_[bucket[i] + 1];
    }
    for (std::uint32_t b = 0; b < size; ++b) bucketStart_[b + 1] += bucketStart_[b];
    photons_.resize(photons.size());
    std::vector<std::uint32_t> next(bucketStart_.begin(), bucketStart_.end() - 1);
    for (std::size_t i = 0; i < photons.size(); ++i) photons_[next[bucket[i]]++] = photons[i];
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

std::uint32_t CausticGrid::bucketOf(glm::vec3 p) const {
    const glm::dvec3 scaled = glm::dvec3(p) * double(invCell_);
    return hashCell(std::int64_t(std::floor(scaled.x)), std::int64_t(std::floor(scaled.y)),
                    std::int64_t(std::floor(scaled.z))) &
           mask_;
}

}  // namespace igi
