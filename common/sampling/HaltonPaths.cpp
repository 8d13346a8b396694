#include "sampling/HaltonPaths.h"

#include <array>
#include <cmath>

#include "sampling/Hash.h"
#include "sampling/Scramble.h"

namespace igi {
namespace {

// Emission: direction (2, 3), light choice (5), point on the light (7, 11); then per bounce:
// direction (two bases), lobe or roulette (one).
constexpr std::array<std::uint32_t, 32> kPrimes = {2,  3,  5,  7,   11,  13,  17,  19,  23,  29, 31,
                                                   37, 41, 43, 47,  53,  59,  61,  67,  71,  73, 79,
                                                   83, 89, 97, 101, 103, 107, 109, 113, 127, 131};
constexpr std::array<unsigned, LightPathNumbers::kEmissionDims> kEmissionOrder = {2, 3, 4, 0, 1};

constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

}  // namespace

double radicalInverse(std::uint32_t i, std::uint32_t b) {
    const double inv = 1.0 / double(b);
    double scale = inv, value = 0;
    while (i > 0) {
        value += double(i % b) * scale;
        i /= b;
        scale *= inv;
    }
    return value;
}

std::uint32_t HaltonPaths::base(unsigned d) {
    // Dimension d's rank in the order above: the emission's own order, then the bounces as
    // they come.
    const unsigned rank = d < kEmissionDims ? kEmissionOrder[d] : d;
    return rank < kPrimes.size() ? kPrimes[rank] : 0;
}

HaltonPaths::HaltonPaths(std::uint64_t seed, std::uint32_t groups, std::uint32_t group,
                         std::uint32_t first, std::uint32_t count)
    : seed_(seed), groups_(groups), group_(group), first_(first), count_(count) {}

float HaltonPaths::sample(std::uint32_t i, unsigned d) const {
    const auto stream = static_cast<std::uint32_t>(SampleStream::SelectivePhotons);
    const std::uint32_t b = base(d);
    if (b == 0) return float(hashValues(seed_, stream, i, d) >> 40) * 0x1p-24f;
    const double shift = double(hashValues(seed_, stream, d) >> 11) * 0x1p-53;
    double u = radicalInverse(i, b) + shift;
    u -= std::floor(u);
    return std::min(float(u), kOneMinusEpsilon);
}

float HaltonPaths::emission(std::uint32_t path, unsigned dim) const {
    return sample(index(path), dim);
}

float HaltonPaths::bounce(std::uint32_t path, unsigned bounce, unsigned dim) const {
    return sample(index(path), kEmissionDims + (bounce - 1) * kBounceDims + dim);
}

}  // namespace igi
