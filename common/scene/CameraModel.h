#pragma once

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
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

    /// How far `p` is in front of the camera, along the viewing direction (< 0: behind).
    float depth(glm::vec3 p) const { return glm::dot(p - origin_, forward_); }
    /// The image position (in pixels, as direction() takes it) that `p` projects to; only for
    /// depth(p) > 0.
    glm::vec2 pixelOf(glm::vec3 p) const {
        const glm::vec3 d = p - origin_;
        const float z = glm::dot(d, forward_);
        // d = z (forward + sx right_ + sy up_), right_ and up_ orthogonal to forward.
        const float sx = glm::dot(d, right_) / (z * glm::dot(right_, right_));
        const float sy = glm::dot(d, up_) / (z * glm::dot(up_, up_));
        return {0.5f * (sx + 1.0f) * width_, 0.5f * (1.0f - sy) * height_};
    }
    int width() const { return int(width_); }
    int height() const { return int(height_); }

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
