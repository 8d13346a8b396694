#include "modes/photonmap/PhotonMap.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include <glm/geometric.hpp>

#include "math/Warp.h"

namespace igi {
namespace {

constexpr float kSameSide = 0.5f;  // cos 60 degrees
constexpr int kMaxShell = 4;       // cells out from the query's own, at most

// The cell of a coordinate, kept within what an int64 holds whatever the cell size.
std::int64_t cellOf(double v) {
    return std::int64_t(std::clamp(std::floor(v), -1e15, 1e15));
}

struct Candidate {
    float d2;
    std::uint32_t index;
};

}  // namespace

PhotonMap::PhotonMap(std::vector<Vpl> hits, double area, int k) : k_(std::max(1, k)) {
    if (hits.empty()) return;
    // The radius that holds k hits where they are spread evenly over the area.
    double r =
        std::sqrt(double(k_) * std::max(area, 1e-30) / (3.14159265358979 * double(hits.size())));
    // Not below a ten-thousandth of the hits' extent: the area is that of the scene as loaded,
    // which is 0 when it had no diffuse surface and a change made one so.
    glm::vec3 lo = hits[0].position, hi = lo;
    for (const Vpl& h : hits) lo = glm::min(lo, h.position), hi = glm::max(hi, h.position);
    r = std::max({r, 1e-4 * double(glm::length(hi - lo)), 1e-30});
    cell_ = float(r);
    invCell_ = float(1.0 / r);
    const auto size = std::uint32_t(std::bit_ceil(std::max<std::size_t>(2 * hits.size(), 8)));
    mask_ = size - 1;
    bucketStart_.assign(size + 1, 0);
    std::vector<std::uint32_t> bucket(hits.size());
    for (std::size_t i = 0; i < hits.size(); ++i) {
        const glm::vec3 p = hits[i].position;
        bucket[i] = bucketOf(cellOf(double(p.x) * invCell_), cellOf(double(p.y) * invCell_),
                             cellOf(double(p.z) * invCell_));
        ++bucketStart_[bucket[i] + 1];
    }
    for (std::uint32_t b = 0; b < size; ++b) bucketStart_[b + 1] += bucketStart_[b];
    hits_.resize(hits.size());
    std::vector<std::uint32_t> next(bucketStart_.begin(), bucketStart_.end() - 1);
    for (std::size_t i = 0; i < hits.size(); ++i) hits_[next[bucket[i]]++] = hits[i];
}

std::uint32_t PhotonMap::hashCell(std::int64_t x, std::int64_t y, std::int64_t z) {
    return (static_cast<std::uint32_t>(x) * 73856093u) ^
           (static_cast<std::uint32_t>(y) * 19349663u) ^
           (static_cast<std::uint32_t>(z) * 83492791u);
}

glm::vec3 PhotonMap::radiance(glm::vec3 p, glm::vec3 n) const {
    if (hits_.empty()) return glm::vec3(0.0f);
    const auto cx = cellOf(double(p.x) * invCell_);
    const auto cy = cellOf(double(p.y) * invCell_);
    const auto cz = cellOf(double(p.z) * invCell_);
    std::vector<std::uint32_t> buckets;
    std::vector<Candidate> found;
    for (int shell = 1;; shell *= 2) {
        // Every hit within shell cells of p lies in the cube of cells cx +- shell, ...
        buckets.clear();
        for (std::int64_t z = cz - shell; z <= cz + shell; ++z)
            for (std::int64_t y = cy - shell; y <= cy + shell; ++y)
                for (std::int64_t x = cx - shell; x <= cx + shell; ++x)
                    buckets.push_back(bucketOf(x, y, z));
        std::sort(buckets.begin(), buckets.end());
        buckets.erase(std::unique(buckets.begin(), buckets.end()), buckets.end());
        const float reach = float(shell) * cell_, reach2 = reach * reach;
        found.clear();
        for (std::uint32_t b : buckets)
            for (std::uint32_t i = bucketStart_[b]; i < bucketStart_[b + 1]; ++i) {
                const Vpl& h = hits_[i];
                if (glm::dot(h.normal, n) < kSameSide) continue;
                const glm::vec3 d = h.position - p;
                const float d2 = glm::dot(d, d);
                if (d2 <= reach2) found.push_back({d2, i});
            }
        const bool enough = found.size() >= std::size_t(k_);
        if (!enough && shell < kMaxShell) continue;
        float r2 = reach2;
        auto nearer = [](const Candidate& a, const Candidate& b) {
            return a.d2 < b.d2 || (a.d2 == b.d2 && a.index < b.index);
        };
        if (enough) {
            std::nth_element(found.begin(), found.begin() + (k_ - 1), found.end(), nearer);
            r2 = found[std::size_t(k_ - 1)].d2;
            found.resize(std::size_t(k_));
        }
        // Hits on top of each other: no density below a thousandth of a cell's radius.
        r2 = std::max(r2, 1e-6f * cell_ * cell_);
        if (!(r2 > 0)) return glm::vec3(0.0f);
        std::sort(found.begin(), found.end(),
                  [](const Candidate& a, const Candidate& b) { return a.index < b.index; });
        glm::vec3 sum(0.0f);
        for (const Candidate& c : found) sum += hits_[c.index].power;
        return sum / (kPi * r2);
    }
}

}  // namespace igi
