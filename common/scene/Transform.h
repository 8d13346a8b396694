#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace igi {

/// An object's placement: scale, then rotation about X, then Y, then Z (degrees), then
/// translation.
struct Transform {
    glm::vec3 translate{0.0f};
    glm::vec3 rotateDeg{0.0f};
    glm::vec3 scale{1.0f};

    glm::mat4 matrix() const;
    bool operator==(const Transform&) const = default;
};

}  // namespace igi
