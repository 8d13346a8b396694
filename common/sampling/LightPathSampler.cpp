#include "sampling/LightPathSampler.h"

#include <numeric>

#include "sampling/Sobol.h"

namespace igi {

LightPathSampler::LightPathSampler(std::uint64_t seed, std::uint32_t frame, SampleStream stream,
                                   std::uint32_t setIndex, std::uint32_t pathsPerSet,
                                   std::uint32_t maxBounces)
    : firstIndex_(setIndex * pathsPerSet), paths_(pathsPerSet) {
    for (unsigned d = 0; d < kEmissionDims; ++d)
        emissionScramble_[d] = scrambleBits(seed, frame, stream, d);

    // Bounce dimensions are numbered after the emission ones so their bit vectors differ.
    bounceScrambles_.resize(std::size_t(maxBounces) * kBounceDims);
    for (std::uint32_t b = 0; b < maxBounces; ++b)
        for (unsigned d = 0; d < kBounceDims; ++d)
            bounceScrambles_[b * kBounceDims + d] =
                scrambleBits(seed, frame, stream, kEmissionDims + b * kBounceDims + d);

    // One random permutation of the set's points per bounce (Fisher-Yates from a generator
    // seeded by the set and bounce, identical on every client).
    permutations_.resize(std::size_t(maxBounces) * pathsPerSet);
    for (std::uint32_t b = 0; b < maxBounces; ++b) {
        auto first = permutations_.begin() + std::ptrdiff_t(b) * pathsPerSet;
        std::iota(first, first + pathsPerSet, 0u);
        SplitMix64 rng(hashValues(seed, frame, static_cast<std::uint32_t>(stream), setIndex, b));
        for (std::uint32_t i = pathsPerSet; i > 1; --i)
            std::swap(first[i - 1], first[rng.below(i)]);
    }
}

float LightPathSampler::emission(std::uint32_t path, unsigned dim) const {
    return Sobol::scrambled(firstIndex_ + path, dim, emissionScramble_[dim]);
}

float LightPathSampler::bounce(std::uint32_t path, unsigned bounce, unsigned dim) const {
    const std::size_t b = bounce - 1;
    const std::uint32_t replicated = permutations_[b * paths_ + path];
    return Sobol::scrambled(firstIndex_ + replicated, dim, bounceScrambles_[b * kBounceDims + dim]);
}

}  // namespace igi
