#include "render/DiscontinuityFilter.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace igi {

void discontinuityFilterRows(const FrameBuffer& f, const DiscontinuityFilterSettings& s,
                             int rowBegin, int rowEnd, std::vector<glm::vec3>& out) {
    // The window [x - left, x + right] has sizeX columns; for an even size it leans left, the
    // same way for every pixel, so it always covers sizeX consecutive interleaving columns.
    const int left = (s.sizeX - 1) / 2, right = s.sizeX - 1 - left;
    const int up = (s.sizeY - 1) / 2, down = s.sizeY - 1 - up;
    for (int y = rowBegin; y < rowEnd; ++y) {
        for (int x = 0; x < f.width; ++x) {
            const std::size_t p = std::size_t(y) * f.width + x;
            const float d = f.depth[p];
            if (!std::isfinite(d)) {  // the eye path ended nowhere: nothing to filter
                out[p] = f.unfiltered[p];
                continue;
            }
            const glm::vec3 n = f.normal[p];
            const float tolerance = s.depthThreshold * d;
            glm::vec3 sum(0.0f);
            int count = 0;
            for (int qy = std::max(0, y - up); qy <= std::min(f.height - 1, y + down); ++qy) {
                for (int qx = std::max(0, x - left); qx <= std::min(f.width - 1, x + right); ++qx) {
                    const std::size_t q = std::size_t(qy) * f.width + qx;
                    if (std::fabs(f.depth[q] - d) > tolerance) continue;  // also rejects +inf
                    if (glm::dot(f.normal[q], n) < s.normalThreshold) continue;
                    sum += f.irradiance[q];
                    ++count;
                }
            }
            // The pixel itself always passes unless its normal is zero (no normal sent), in
            // which case it stands alone.
            const glm::vec3 irradiance = count > 0 ? sum / float(count) : f.irradiance[p];
            out[p] = f.reflectance[p] * irradiance + f.unfiltered[p];
        }
    }
}

}  // namespace igi
