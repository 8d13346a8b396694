#pragma once

#include <cstdint>

namespace igi {

/// The random numbers of a batch of light paths: what a light path tracer
/// (LightingSetBuilder::traceLightPaths) asks for, whichever sequence they come from. IGI's
/// per-frame sets draw them from Sobol' points (LightPathSampler); selective photon tracing
/// from a Halton sequence whose periodicity groups similar paths (HaltonPaths).
class LightPathNumbers {
  public:
    /// Emission dimensions: light choice, point on the light (2), direction (2).
    static constexpr unsigned kEmissionDims = 5;
    /// Per bounce: direction (2), lobe choice or Russian roulette (1).
    static constexpr unsigned kBounceDims = 3;

    virtual ~LightPathNumbers() = default;

    /// Emission sample `dim` (< kEmissionDims) of path `path` (< paths()), in [0, 1).
    virtual float emission(std::uint32_t path, unsigned dim) const = 0;
    /// Sample `dim` (< kBounceDims) of bounce `bounce` (1, 2, ...) of path `path`, in [0, 1).
    virtual float bounce(std::uint32_t path, unsigned bounce, unsigned dim) const = 0;
    /// The paths of the batch.
    virtual std::uint32_t pathsPerSet() const = 0;
};

}  // namespace igi
