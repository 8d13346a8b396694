#pragma once

#include <algorithm>
#include <cstdint>

namespace igi {

/// The Sobol' sequence with Joe-Kuo direction numbers (the table Boost ships), in natural
/// order: point i is the XOR of the direction numbers of the bits set in i. Random access, so
/// any sample can be replayed from its index alone.
class Sobol {
  public:
    static constexpr unsigned kMaxDimensions = 256;

    /// The 32-bit fixed-point value of point `index` in `dimension` (< kMaxDimensions).
    static std::uint32_t sample(std::uint32_t index, unsigned dimension);

    /// Converts a fixed-point sample to [0, 1). A 32-bit value times 2^-32 rounds to 1.0 in
    /// float for values near 2^32, so the result is clamped below one.
    static float toFloat(std::uint32_t value) {
        return std::min(static_cast<float>(value) * 0x1p-32f, 0x1.fffffep-1f);
    }

    /// An XOR-randomized sample in [0, 1): Kollig and Keller's minimal randomization.
    static float scrambled(std::uint32_t index, unsigned dimension, std::uint32_t scramble) {
        return toFloat(sample(index, dimension) ^ scramble);
    }
};

}  // namespace igi
