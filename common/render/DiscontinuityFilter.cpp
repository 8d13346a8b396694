#include "render/DiscontinuityFilter.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace igi {

int filterWindowStart(int centre, int size, int extent) {
    const int start = centre - (size - 1) / 2;
    return std::clamp(start, 0, std::max(0, extent - size));
}

void discontinuityFilterRows(const FrameBuffer& f, const DiscontinuityFilterSettings& s,
                             int rowBegin, int rowEnd, std::vector<glm::vec3>& out) {
    for (int y = rowBegin; y < rowEnd; ++y) {
        const int y0 = filterWindowStart(y, s.sizeY, f.height),
                  y1 = std::min(f.height, y0 + s.sizeY);
        for (int x = 0; x < f.width; ++x) {
            const std::size_t p = std::size_t(y) * f.width + x;
            const float d = f.depth[p];
            if (!std::isfinite(d)) {  // the eye path ended nowhere: nothing to filter
                out[p] = f.unfiltered[p];
                continue;
            }
            const int x0 = filterWindowStart(x, s.sizeX, f.width),
                      x1 = std::min(f.width, x0 + s.sizeX);
            const glm::vec3 n = f.normal[p];
            const float tolerance = s.depthThreshold * d;
            glm::vec3 sum(0.0f), glossySum(0.0f);
            int count = 0;
            for (int qy = y0; qy < y1; ++qy) {
                for (int qx = x0; qx < x1; ++qx) {
                    const std::size_t q = std::size_t(qy) * f.width + qx;
                    if (std::fabs(f.depth[q] - d) > tolerance) continue;  // also rejects +inf
                    if (glm::dot(f.normal[q], n) < s.normalThreshold) continue;
                    sum += f.irradiance[q];
                    glossySum += f.glossy[q];
                    ++count;
                }
            }
            // The pixel itself passes unless it has no normal; then it stands alone.
            const glm::vec3 irradiance = count > 0 ? sum / float(count) : f.irradiance[p];
            const glm::vec3 glossy = count > 0 ? glossySum / float(count) : f.glossy[p];
            out[p] = f.reflectance[p] * irradiance + glossy + f.unfiltered[p];
        }
    }
}

void compositeUnfilteredRows(const FrameBuffer& f, int rowBegin, int rowEnd,
                             std::vector<glm::vec3>& out) {
    for (std::size_t p = std::size_t(rowBegin) * f.width; p < std::size_t(rowEnd) * f.width; ++p)
        out[p] = f.reflectance[p] * f.irradiance[p] + f.glossy[p] + f.unfiltered[p];
}

}  // namespace igi
