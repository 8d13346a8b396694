#include "render/FrameBuffer.h"

#include <limits>

namespace igi {

void FrameBuffer::reset(int w, int h) {
    width = w;
    height = h;
    const std::size_t n = std::size_t(w) * std::size_t(h);
    irradiance.assign(n, glm::vec3(0.0f));
    reflectance.assign(n, glm::vec3(0.0f));
    normal.assign(n, glm::vec3(0.0f));
    depth.assign(n, std::numeric_limits<float>::infinity());
    unfiltered.assign(n, glm::vec3(0.0f));
    glossy.assign(n, glm::vec3(0.0f));
}

void FrameBuffer::scatter(const Tile& tile, int n, int m, const TileChannels& c) {
    const int count = tile.pixelCount(n, m);
    for (int i = 0; i < count; ++i) {
        const std::size_t p = std::size_t(tile.pixelY(i, n, m)) * width + tile.pixelX(i, n);
        irradiance[p] = c.irradiance.empty() ? glm::vec3(0.0f) : c.irradiance[i];
        reflectance[p] = c.reflectance.empty() ? glm::vec3(0.0f) : c.reflectance[i];
        normal[p] = c.normal.empty() ? glm::vec3(0.0f) : c.normal[i];
        depth[p] = c.depth.empty() ? std::numeric_limits<float>::infinity() : c.depth[i];
        unfiltered[p] = c.unfiltered.empty() ? glm::vec3(0.0f) : c.unfiltered[i];
        glossy[p] = c.glossy.empty() ? glm::vec3(0.0f) : c.glossy[i];
    }
}

}  // namespace igi
