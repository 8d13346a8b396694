#pragma once

#include <limits>

#include <glm/vec3.hpp>

namespace igi {

/// One pixel's planes (see render/TileChannels.h): the master shows
/// reflectance * filtered(irradiance) + filtered(glossy) + unfiltered.
struct PixelResult {
    glm::vec3 irradiance{0.0f};
    glm::vec3 reflectance{0.0f};
    glm::vec3 normal{0.0f};
    float depth = std::numeric_limits<float>::infinity();
    glm::vec3 unfiltered{0.0f};
    glm::vec3 glossy{0.0f};
    /// Whether the filtered end point is the eye ray's first hit (not seen through a mirror or
    /// glass): screen-space caustics apply to it.
    bool firstHit = false;
};

}  // namespace igi
