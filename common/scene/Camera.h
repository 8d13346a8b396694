#pragma once

#include <glm/vec3.hpp>

namespace igi {

/// A pinhole camera; the aspect ratio comes from the image size.
struct Camera {
    glm::vec3 position{0.0f, 0.0f, 1.0f};
    glm::vec3 lookAt{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fovYDeg = 45.0f;  ///< vertical field of view in degrees

    bool operator==(const Camera&) const = default;
};

}  // namespace igi
