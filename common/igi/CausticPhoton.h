#pragma once

#include <glm/vec3.hpp>

namespace igi {

/// A photon that reached a diffuse surface after at least one mirror or glass bounce.
struct CausticPhoton {
    glm::vec3 position{0.0f};
    glm::vec3 direction{0.0f};  ///< direction of travel when it arrived
    glm::vec3 power{0.0f};      ///< flux it carries (W), already divided by the photon count
    glm::vec3 normal{0.0f};     ///< the surface's geometric normal on the side it arrived at
};

}  // namespace igi
