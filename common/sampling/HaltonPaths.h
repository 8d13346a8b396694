#pragma once

#include <cstdint>
#include <vector>

#include "sampling/LightPathNumbers.h"

namespace igi {

/// The light paths of selective photon tracing (Dmitriev et al. 2002, section 4): path i of the
/// session draws dimension d from the radical inverse of i in the d-th prime base, shifted by a
/// per-dimension random offset (Cranley-Patterson, from the session seed) modulo 1.
///
/// The paper's periodicity (its equations 3 and 5): for G = 2^a 3^b ..., paths i and i + m G
/// agree in the dimension of base 2 to within 2^-a, in that of base 3 to within 3^-b, and so
/// on; the shift keeps that modulo 1. So the paths g, g + G, g + 2G, ... (group g) start in
/// the same small box of those dimensions and tend to go the same way: what one of them (a
/// pilot) meets, the others of its group are likely to meet too.
///
/// The bases go to the dimensions in the order in which they decide where a path goes for our
/// lights: the emission direction first (bases 2 and 3), then the light choice (5), then the
/// point on the light (7, 11), then the bounces. Past the primes tabled, a dimension is a hash
/// of (seed, i, d): high Halton dimensions are poorly distributed anyway, and nothing groups
/// on them.
class HaltonPaths final : public LightPathNumbers {
  public:
    /// The paths g + (first + j) G, j = 0 .. count - 1, of group g of G.
    HaltonPaths(std::uint64_t seed, std::uint32_t groups, std::uint32_t group, std::uint32_t first,
                std::uint32_t count);

    float emission(std::uint32_t path, unsigned dim) const override;
    float bounce(std::uint32_t path, unsigned bounce, unsigned dim) const override;
    std::uint32_t pathsPerSet() const override { return count_; }

    /// The sequence index of path j.
    std::uint32_t index(std::uint32_t path) const { return group_ + (first_ + path) * groups_; }
    /// Dimension d (emission dims first, then kBounceDims per bounce) of sequence index i.
    float sample(std::uint32_t i, unsigned d) const;

    /// The prime base of dimension d (0 past the table: hashed).
    static std::uint32_t base(unsigned d);

  private:
    std::uint64_t seed_;
    std::uint32_t groups_, group_, first_, count_;
};

/// The radical inverse of i in base b: its base-b digits mirrored about the point.
double radicalInverse(std::uint32_t i, std::uint32_t b);

}  // namespace igi
