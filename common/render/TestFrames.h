#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "render/DiscontinuityFilter.h"
#include "render/FrameBuffer.h"

namespace igi::test {

/// The buffer as the paper describes it, one pixel and one neighbour at a time: what the
/// eight-wide kernels must reproduce bit for bit.
inline std::vector<glm::vec3> referenceFilter(const FrameBuffer& f, DiscontinuityFilterSettings s) {
    std::vector<glm::vec3> out(f.depth.size());
    for (int y = 0; y < f.height; ++y) {
        const int y0 = filterWindowStart(y, s.sizeY, f.height);
        for (int x = 0; x < f.width; ++x) {
            const std::size_t p = std::size_t(y) * f.width + x;
            const float d = f.depth[p];
            if (!std::isfinite(d)) {
                out[p] = f.unfiltered[p];
                continue;
            }
            const int x0 = filterWindowStart(x, s.sizeX, f.width);
            glm::vec3 sum(0.0f), glossy(0.0f);
            int count = 0, glossyCount = 0;
            for (int qy = y0; qy < std::min(f.height, y0 + s.sizeY); ++qy)
                for (int qx = x0; qx < std::min(f.width, x0 + s.sizeX); ++qx) {
                    const std::size_t q = std::size_t(qy) * f.width + qx;
                    if (std::fabs(f.depth[q] - d) > s.depthThreshold * d) continue;
                    const float dot = glm::dot(f.normal[q], f.normal[p]);
                    if (dot < s.normalThreshold) continue;
                    sum += f.irradiance[q];
                    ++count;
                    if (dot < s.glossyNormalThreshold) continue;  // glossy: nearly the same normal
                    glossy += f.glossy[q];
                    ++glossyCount;
                }
            const glm::vec3 e = count > 0 ? sum / float(count) : f.irradiance[p];
            const glm::vec3 g = glossyCount > 0 ? glossy / float(glossyCount) : f.glossy[p];
            out[p] = f.reflectance[p] * e + g + f.unfiltered[p];
        }
    }
    return out;
}

/// A frame of noisy irradiance on surfaces that break in depth and in normal, with misses
/// (+inf, and now and then NaN or -inf depth) and pixels without a normal.
inline FrameBuffer randomFrame(int w, int h, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    FrameBuffer f;
    f.reset(w, h);
    for (std::size_t p = 0; p < f.depth.size(); ++p) {
        const float r = u(rng);
        f.depth[p] = r < 0.05f    ? std::numeric_limits<float>::infinity()
                     : r < 0.06f  ? std::numeric_limits<float>::quiet_NaN()
                     : r < 0.065f ? -std::numeric_limits<float>::infinity()
                                  : (r < 0.5f ? 2.0f : 2.06f) + 0.01f * u(rng);
        f.normal[p] =
            u(rng) < 0.8f ? glm::vec3(0, 0, 1) : glm::normalize(glm::vec3(u(rng), u(rng), 1.0f));
        if (u(rng) < 0.03f) f.normal[p] = glm::vec3(0.0f);  // no normal: stands alone
        f.irradiance[p] = glm::vec3(u(rng), u(rng), u(rng)) * 3.0f;
        f.reflectance[p] = glm::vec3(u(rng), u(rng), u(rng));
        f.glossy[p] = u(rng) < 0.5f ? glm::vec3(u(rng), u(rng), u(rng)) : glm::vec3(0.0f);
        f.unfiltered[p] = u(rng) < 0.2f ? glm::vec3(u(rng)) : glm::vec3(0.0f);
    }
    return f;
}

}  // namespace igi::test
