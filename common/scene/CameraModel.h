#pragma once

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "math/Lanes.h"
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

    /// direction(px[i], py[i]) for i < n, into out[i], four at a time: the same operations
    /// lane by lane (glm's dot is (x x' + y y') + z z', its normalize v (1 / sqrt(v.v))), so the
    /// same bits, without waiting on each direction's divisions and square root in turn.
    void directions(const float* px, const float* py, int n, glm::vec3* out) const {
        using lanes::F4;
        int i = 0;
        for (; i + 4 <= n; i += 4) {
            const F4 x = lanes::load<F4>(px + i), y = lanes::load<F4>(py + i);
            const F4 sx = 2.0f * x / width_ - 1.0f;
            const F4 sy = 1.0f - 2.0f * y / height_;
            const F4 vx = (forward_.x + sx * right_.x) + sy * up_.x;
            const F4 vy = (forward_.y + sx * right_.y) + sy * up_.y;
            const F4 vz = (forward_.z + sx * right_.z) + sy * up_.z;
            const F4 inverse = 1.0f / lanes::squareRoot((vx * vx + vy * vy) + vz * vz);
            const F4 ux = vx * inverse, uy = vy * inverse, uz = vz * inverse;
            for (int k = 0; k < 4; ++k) out[i + k] = glm::vec3(ux[k], uy[k], uz[k]);
        }
        for (; i < n; ++i) out[i] = direction(px[i], py[i]);
    }

  private:
    glm::vec3 origin_;
    glm::vec3 forward_{0.0f}, right_{0.0f}, up_{0.0f};
    float width_, height_;
};

}  // namespace igi
