#pragma once

#include <cstdint>

namespace igi {

/// SplitMix64's finalizer: a bijective 64-bit mixer with good avalanche.
constexpr std::uint64_t mix64(std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/// Hashes a sequence of integers into 64 bits; the same arguments give the same value on every
/// machine, which is how clients agree on random bit vectors without talking to each other.
template <typename... Ts>
constexpr std::uint64_t hashValues(std::uint64_t first, Ts... rest) {
    std::uint64_t h = mix64(first + 0x9e3779b97f4a7c15ull);
    ((h = mix64(h ^ (static_cast<std::uint64_t>(rest) + 0x9e3779b97f4a7c15ull))), ...);
    return h;
}

/// A small counter-based generator for things that need a stream (permutations).
class SplitMix64 {
  public:
    explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
    std::uint64_t next() { return mix64(state_ += 0x9e3779b97f4a7c15ull); }
    /// Uniform integer in [0, bound), bound > 0 (Lemire's multiply-shift; the bias is < 2^-32
    /// for the small bounds used here).
    std::uint32_t below(std::uint32_t bound) {
        return static_cast<std::uint32_t>(((next() >> 32) * bound) >> 32);
    }
    float uniform() { return static_cast<float>(next() >> 40) * 0x1p-24f; }

  private:
    std::uint64_t state_;
};

}  // namespace igi
