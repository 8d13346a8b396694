#include "render/FrameBuffer.h"

#include <limits>

namespace igi {
namespace {

constexpr float kNoDepth = std::numeric_limits<float>::infinity();

}  // namespace

void FrameBuffer::reset(int w, int h) {
    width = w;
    height = h;
    const std::size_t n = std::size_t(w) * std::size_t(h);
    irradiance.assign(n, glm::vec3(0.0f));
    reflectance.assign(n, glm::vec3(0.0f));
    normal.assign(n, glm::vec3(0.0f));
    depth.assign(n, kNoDepth);
    unfiltered.assign(n, glm::vec3(0.0f));
    glossy.assign(n, glm::vec3(0.0f));
    live.bits = kAllChannels;
}

void FrameBuffer::reuse(int w, int h) {
    if (w == width && h == height && depth.size() == std::size_t(w) * std::size_t(h)) return;
    reset(w, h);
    live.bits = 0;
}

namespace {

/// Writes one plane of a tile, row by row of its strided grid. An empty `source` (the tile did
/// not send the plane) writes `empty`, unless the plane is empty in the whole buffer already.
template <typename T>
void scatterPlane(std::vector<T>& plane, const std::vector<T>& source, T empty, Channel bit,
                  FrameBuffer::LiveMask& live, const Tile& tile, int width, int n, int m) {
    if (source.empty() && !live.has(bit)) return;
    // A plane comes to life before its values land: a thread that reads a clear bit skips only
    // pixels that no earlier frame wrote, so they are empty already.
    if (!source.empty()) live.bits.fetch_or(bit, std::memory_order_relaxed);
    const int columns = tile.columns(n), rows = tile.rows(m);
    for (int r = 0; r < rows; ++r) {
        T* out = plane.data() + std::size_t(tile.y0 + tile.ky + r * m) * width + tile.x0 + tile.kx;
        if (source.empty()) {
            for (int c = 0; c < columns; ++c) out[std::size_t(c) * n] = empty;
        } else {
            const T* in = source.data() + std::size_t(r) * columns;
            for (int c = 0; c < columns; ++c) out[std::size_t(c) * n] = in[c];
        }
    }
}

}  // namespace

void FrameBuffer::scatter(const Tile& tile, int n, int m, const TileChannels& c) {
    const glm::vec3 zero(0.0f);
    scatterPlane(irradiance, c.irradiance, zero, kIrradiance, live, tile, width, n, m);
    scatterPlane(reflectance, c.reflectance, zero, kReflectance, live, tile, width, n, m);
    scatterPlane(normal, c.normal, zero, kNormal, live, tile, width, n, m);
    scatterPlane(depth, c.depth, kNoDepth, kDepth, live, tile, width, n, m);
    scatterPlane(unfiltered, c.unfiltered, zero, kUnfiltered, live, tile, width, n, m);
    scatterPlane(glossy, c.glossy, zero, kGlossy, live, tile, width, n, m);
}

}  // namespace igi
