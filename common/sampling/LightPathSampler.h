#pragma once

#include <cstdint>
#include <vector>

#include "sampling/LightPathNumbers.h"
#include "sampling/Scramble.h"

namespace igi {

/// Randomized quasi-Monte Carlo samples for the light paths of one interleaving set k.
///
/// Set k owns points [k*N, (k+1)*N) of one XOR-randomized Sobol' sequence of the frame, so the
/// sets of all k together are a prefix of that sequence and complement each other when the
/// discontinuity buffer joins neighbouring pixels (paper, section 4.4). The emission of a path
/// (light choice, point on the light, direction) uses the first kEmissionDims dimensions of that
/// Sobol' point. Each further bounce uses padded replications (Kollig and Keller 2002): the
/// same low-dimensional points of the set, in a random order of their own and with their own
/// random bit vectors, which avoids the poor projections of high Sobol' dimensions.
class LightPathSampler final : public LightPathNumbers {
  public:
    LightPathSampler(std::uint64_t seed, std::uint32_t frame, SampleStream stream,
                     std::uint32_t setIndex, std::uint32_t pathsPerSet, std::uint32_t maxBounces);

    /// Emission sample `dim` (< kEmissionDims) of path `path` (< pathsPerSet), in [0, 1).
    float emission(std::uint32_t path, unsigned dim) const override;
    /// Sample `dim` (< kBounceDims) of bounce `bounce` (1 .. maxBounces) of path `path`.
    float bounce(std::uint32_t path, unsigned bounce, unsigned dim) const override;

    std::uint32_t pathsPerSet() const override { return paths_; }

  private:
    std::uint32_t firstIndex_;
    std::uint32_t paths_;
    std::uint32_t emissionScramble_[kEmissionDims];
    std::vector<std::uint32_t> bounceScrambles_;  ///< [bounce - 1][dim]
    std::vector<std::uint32_t> permutations_;     ///< [bounce - 1][path]
};

}  // namespace igi
