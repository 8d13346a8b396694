#pragma once

#include <cstdint>

#include "sampling/Hash.h"
#include "sampling/Scramble.h"
#include "sampling/Sobol.h"

namespace igi {

/// The random numbers of one pixel's eye path, reproducible from (seed, pixel, sample index):
/// any pixel can be re-rendered anywhere with the same result. The first two dimensions (the
/// position inside the pixel) follow a Sobol' sequence over sample indices, XOR-scrambled per
/// pixel, so accumulated frames anti-alias in a stratified way; later dimensions (choices at
/// specular bounces, glossy directions) are hashed.
class PixelSampler {
  public:
    PixelSampler(std::uint64_t seed, SampleStream stream, std::uint32_t pixel, std::uint32_t sample)
        : key_(hashValues(seed, static_cast<std::uint32_t>(stream), pixel)), sample_(sample) {}

    float get(std::uint32_t dimension) const {
        if (dimension < 2) {
            const auto scramble = static_cast<std::uint32_t>(hashValues(key_, dimension) >> 32);
            return Sobol::scrambled(sample_, dimension, scramble);
        }
        return Sobol::toFloat(
            static_cast<std::uint32_t>(hashValues(key_, sample_, dimension) >> 32));
    }

  private:
    std::uint64_t key_;
    std::uint32_t sample_;
};

}  // namespace igi
