#include "modes/photonmap/ScreenCaustics.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "lights/Vpl.h"
#include "math/Warp.h"

namespace igi {

ScreenCaustics::ScreenCaustics(const TraceableScene& scene, const Camera& camera, int width,
                               int height, std::vector<CausticPhoton> photons, int halfWidth)
    : scene_(scene),
      origin_(camera.position),
      width_(width),
      height_(height),
      half_(std::max(0, halfWidth)) {
    // As CameraModel places the image.
    forward_ = glm::normalize(camera.lookAt - camera.position);
    const glm::vec3 right = glm::normalize(glm::cross(forward_, camera.up));
    const glm::vec3 up = glm::cross(right, forward_);
    const float halfHeight = std::tan(0.5f * camera.fovYDeg * kPi / 180.0f);
    const float halfWidthPlane = halfHeight * float(width) / float(height);
    right_ = right * halfWidthPlane;
    up_ = up * halfHeight;
    pixelArea_ = (2.0f * halfWidthPlane / float(width)) * (2.0f * halfHeight / float(height));

    float total = 0;
    for (int j = -half_; j <= half_; ++j)
        for (int i = -half_; i <= half_; ++i) {
            const float w = std::sqrt(float(1 + 2 * half_ * half_ - (i * i + j * j)));
            weights_.push_back(w);
            total += w;
        }
    for (float& w : weights_) w /= total;

    // Project every photon in front of the camera whose window reaches the image.
    for (const CausticPhoton& p : photons) {
        const glm::vec3 d = p.position - origin_;
        const float z = glm::dot(d, forward_);
        if (!(z > 0)) continue;
        const float sx = glm::dot(d, right) / (z * halfWidthPlane);
        const float sy = glm::dot(d, up) / (z * halfHeight);
        const float px = 0.5f * (sx + 1.0f) * float(width), py = 0.5f * (1.0f - sy) * float(height);
        if (!(px > -float(half_ + 1) && px < float(width + half_ + 1) && py > -float(half_ + 1) &&
              py < float(height + half_ + 1)))
            continue;
        photons_.push_back(
            {p.position, p.power, p.normal, int(std::floor(px)), int(std::floor(py))});
    }
    visibility_.reset(new std::atomic<std::uint8_t>[photons_.size()]);
    for (std::size_t i = 0; i < photons_.size(); ++i) visibility_[i].store(0);

    // Buckets of kCell x kCell pixels (with the margin) for the pixels' lookups.
    cellsX_ = (width + 2 * (half_ + 1)) / kCell + 1;
    cellsY_ = (height + 2 * (half_ + 1)) / kCell + 1;
    auto cellOf = [&](const Splat& s) {
        const int cx = std::clamp((s.x + half_ + 1) / kCell, 0, cellsX_ - 1);
        const int cy = std::clamp((s.y + half_ + 1) / kCell, 0, cellsY_ - 1);
        return std::size_t(cy * cellsX_ + cx);
    };
    bucketStart_.assign(std::size_t(cellsX_ * cellsY_) + 1, 0);
    for (const Splat& s : photons_) ++bucketStart_[cellOf(s) + 1];
    for (std::size_t c = 1; c < bucketStart_.size(); ++c) bucketStart_[c] += bucketStart_[c - 1];
    sorted_.resize(photons_.size());
    std::vector<std::uint32_t> next(bucketStart_.begin(), bucketStart_.end() - 1);
    for (std::size_t i = 0; i < photons_.size(); ++i)
        sorted_[next[cellOf(photons_[i])]++] = std::uint32_t(i);
}

glm::vec3 ScreenCaustics::ray(float px, float py) const {
    const float sx = 2.0f * px / float(width_) - 1.0f;
    const float sy = 1.0f - 2.0f * py / float(height_);
    return forward_ + sx * right_ + sy * up_;
}

float ScreenCaustics::footprint(int x, int y, float distance, glm::vec3 normal) const {
    const glm::vec3 r = ray(float(x) + 0.5f, float(y) + 0.5f);
    const float length = glm::length(r);
    // The pixel's solid angle (its area on the plane at distance 1 seen obliquely), times the
    // squared distance, over the cosine at the surface.
    const float solidAngle = pixelArea_ / (length * length * length);
    const float cosSurface = std::max(0.05f, std::fabs(glm::dot(normal, r / length)));
    return solidAngle * distance * distance / cosSurface;
}

bool ScreenCaustics::visible(std::uint32_t i, RayCounters& counters) const {
    std::uint8_t state = visibility_[i].load(std::memory_order_relaxed);
    if (state == 0) {
        // Every client and thread finds the same answer: storing it twice is harmless.
        const Splat& s = photons_[i];
        const glm::vec3 toPhoton = s.position - origin_;
        const float d = glm::length(toPhoton);
        bool seen = d > 0 && glm::dot(s.normal, toPhoton) < 0;  // the side it arrived at
        if (seen)
            seen = !scene_.occluded(origin_, toPhoton / d, d * (1.0f - kVplShadowShrink), counters);
        state = seen ? 1 : 2;
        visibility_[i].store(state, std::memory_order_relaxed);
    }
    return state == 1;
}

glm::vec3 ScreenCaustics::irradiance(int x, int y, float footprint, RayCounters& counters) const {
    if (photons_.empty() || !(footprint > 0)) return glm::vec3(0.0f);
    const int n = 2 * half_ + 1;
    const int c0x = std::clamp((x - half_ + half_ + 1) / kCell, 0, cellsX_ - 1);
    const int c1x = std::clamp((x + half_ + half_ + 1) / kCell, 0, cellsX_ - 1);
    const int c0y = std::clamp((y - half_ + half_ + 1) / kCell, 0, cellsY_ - 1);
    const int c1y = std::clamp((y + half_ + half_ + 1) / kCell, 0, cellsY_ - 1);
    glm::vec3 flux(0.0f);
    for (int cy = c0y; cy <= c1y; ++cy)
        for (int cx = c0x; cx <= c1x; ++cx) {
            const std::size_t c = std::size_t(cy * cellsX_ + cx);
            for (std::uint32_t k = bucketStart_[c]; k < bucketStart_[c + 1]; ++k) {
                const std::uint32_t i = sorted_[k];
                const Splat& s = photons_[i];
                const int dx = x - s.x, dy = y - s.y;
                if (dx < -half_ || dx > half_ || dy < -half_ || dy > half_) continue;
                if (!visible(i, counters)) continue;
                flux += s.power * weights_[std::size_t((dy + half_) * n + (dx + half_))];
            }
        }
    return flux / footprint;
}

}  // namespace igi
