#pragma once

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "math/Warp.h"
#include "scene/Camera.h"

namespace igi {

/// A pinhole camera's rays: pixel (0, 0) is the top-left corner of the image.
class CameraModel {
  public:
    CameraModel(const Camera& camera, int width, int height)
        : origin_(camera.position), width_(float(width)), height_(float(height)) {
        const glm::vec3 forward = glm::normalize(camera.lookAt - camera.position);
        const glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
        const glm::vec3 up = glm::cross(right, forward);
        const float halfHeight = std::tan(0.5f * camera.fovYDeg * kPi / 180.0f);
        const float halfWidth = halfHeight * width_ / height_;
        forward_ = forward;
        right_ = right * halfWidth;
        up_ = up * halfHeight;
    }

    glm::vec3 origin() const { return origin_; }

    /// Unit direction through image position (px, py), in pixels.
    glm::vec3 direction(float px, float py) const {
        const float sx = 2.0f * px / width_ - 1.0f;
        const float sy = 1.0f - 2.0f * py / height_;
        return glm::normalize(forward_ + sx * right_ + sy * up_);
    }

  private:
    glm::vec3 origin_;
    glm::vec3 forward_{0.0f}, right_{0.0f}, up_{0.0f};
    float width_, height_;
};

}  // namespace igi
