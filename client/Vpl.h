#pragma once

#include <glm/vec3.hpp>

namespace igi {

/// A virtual point light: a point on a light source or a diffuse vertex of a light path.
/// It sends radiant intensity power * cos(theta) (surface VPL, theta from `normal`) or `power`
/// in every direction (omni: a point light), so the irradiance it gives a point at distance d
/// whose normal makes angle theta_x with it is power * cos(theta) * cos(theta_x) / d^2.
struct Vpl {
    glm::vec3 position{0.0f};  ///< already moved off its surface: shadow rays end here
    glm::vec3 normal{0.0f};
    glm::vec3 power{0.0f};
    bool omni = false;
};

}  // namespace igi
