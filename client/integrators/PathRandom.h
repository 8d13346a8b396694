#pragma once

#include <cstdint>

#include <glm/vec2.hpp>

#include "integrators/PixelSampler.h"

namespace igi {

/// The random numbers of a pixel's path beyond its fixed dimensions, handed out in the order
/// they are asked for. The path is computed by one thread in a fixed order, so the same pixel
/// of the same frame gets the same numbers wherever it is rendered.
class PathRandom {
  public:
    PathRandom(const PixelSampler& sampler, std::uint32_t firstDimension)
        : sampler_(sampler), next_(firstDimension) {}

    float next() { return sampler_.get(next_++); }
    /// The dimension the next number comes from: a PathRandom made with it goes on from here.
    std::uint32_t position() const { return next_; }
    glm::vec2 next2() {
        const float a = next();
        return {a, next()};
    }

  private:
    const PixelSampler& sampler_;
    std::uint32_t next_;
};

}  // namespace igi
