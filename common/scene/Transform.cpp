#include "scene/Transform.h"

#include <glm/gtc/matrix_transform.hpp>

namespace igi {

glm::mat4 Transform::matrix() const {
    // Applied right to left: scale, rotate about X, then Y, then Z, then translate.
    glm::mat4 m = glm::translate(glm::mat4(1.0f), translate);
    m = glm::rotate(m, glm::radians(rotateDeg.z), glm::vec3(0, 0, 1));
    m = glm::rotate(m, glm::radians(rotateDeg.y), glm::vec3(0, 1, 0));
    m = glm::rotate(m, glm::radians(rotateDeg.x), glm::vec3(1, 0, 0));
    return glm::scale(m, scale);
}

}  // namespace igi
