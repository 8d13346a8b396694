#include "integrators/LightEdges.h"

#include <algorithm>
#include <cmath>

#include <glm/vec2.hpp>

#include "lights/Lights.h"

namespace igi {

LightEdges::LightEdges(const CameraModel& camera)
    : camera_(camera), width_(camera.width()), height_(camera.height()) {
    mask_.assign(std::size_t(width_) * std::size_t(height_), 0);
}

LightEdges::LightEdges(const Lights& lights, const CameraModel& camera) : LightEdges(camera) {
    lights.forEachTriangle([this](glm::vec3 a, glm::vec3 b, glm::vec3 c) { addTriangle(a, b, c); });
}

void LightEdges::addTriangle(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    if (mask_.empty()) return;
    const glm::vec3 corners[3] = {a, b, c};
    float depth[3];
    float farthest = 0.0f;
    for (int i = 0; i < 3; ++i) {
        depth[i] = camera_.depth(corners[i]);
        farthest = std::max(farthest, depth[i]);
    }
    if (!(farthest > 0.0f)) return;  // behind the camera (or not a number)
    // The part in front of a near plane, relative to the triangle's own depth so that a scene
    // of any size clips alike (Sutherland-Hodgman: at most four corners).
    const float near = 1e-6f * farthest;
    glm::vec3 kept[4];
    int count = 0;
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3;
        const bool in = depth[i] >= near, nextIn = depth[j] >= near;
        if (in) kept[count++] = corners[i];
        if (in != nextIn) {
            const float t = (near - depth[i]) / (depth[j] - depth[i]);
            kept[count++] = corners[i] + t * (corners[j] - corners[i]);
        }
    }
    glm::vec2 projected[4];
    for (int i = 0; i < count; ++i) projected[i] = camera_.pixelOf(kept[i]);
    for (int i = 0; i < count; ++i) {
        const glm::vec2 p = projected[i], q = projected[(i + 1) % count];
        addSegment(p.x, p.y, q.x, q.y);
    }
}

void LightEdges::addSegment(float x0, float y0, float x1, float y1) {
    if (!std::isfinite(x0) || !std::isfinite(y0) || !std::isfinite(x1) || !std::isfinite(y1))
        return;
    // Clipped to the image and a pixel around it (Liang-Barsky), so that a segment that runs
    // far off screen costs no steps there.
    const float dx = x1 - x0, dy = y1 - y0;
    float t0 = 0.0f, t1 = 1.0f;
    const float p[4] = {-dx, dx, -dy, dy};
    const float q[4] = {x0 + 1.0f, float(width_) + 1.0f - x0, y0 + 1.0f,
                        float(height_) + 1.0f - y0};
    for (int k = 0; k < 4; ++k) {
        if (p[k] == 0.0f) {
            if (q[k] < 0.0f) return;  // parallel to that side and outside it
            continue;
        }
        const float t = q[k] / p[k];
        if (p[k] < 0.0f)
            t0 = std::max(t0, t);
        else
            t1 = std::min(t1, t);
        if (t0 > t1) return;
    }
    const float ax = x0 + t0 * dx, ay = y0 + t0 * dy, bx = x0 + t1 * dx, by = y0 + t1 * dy;
    // Points half a pixel apart or closer: every pixel the segment crosses holds one, or is
    // next to the pixel of one, and mark() takes the neighbours.
    const float length = std::max(std::abs(bx - ax), std::abs(by - ay));
    const int steps = int(std::ceil(2.0f * length)) + 1;
    for (int s = 0; s <= steps; ++s) {
        const float t = float(s) / float(steps);
        mark(int(std::floor(ax + t * (bx - ax))), int(std::floor(ay + t * (by - ay))));
    }
}

void LightEdges::mark(int x, int y) {
    for (int j = std::max(0, y - 1); j <= std::min(height_ - 1, y + 1); ++j)
        for (int i = std::max(0, x - 1); i <= std::min(width_ - 1, x + 1); ++i) {
            std::uint8_t& m = mask_[std::size_t(j) * std::size_t(width_) + std::size_t(i)];
            count_ += m == 0;
            m = 1;
        }
}

}  // namespace igi
