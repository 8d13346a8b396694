#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "render/Tile.h"
#include "render/TileChannels.h"

namespace igi {

/// The planes of a whole frame as floats, assembled from tile results; the input of the
/// discontinuity buffer for tests and tools (the master keeps the tiles' wire codes instead and
/// dequantizes them row by row, proto::CodedFrame, to the same floats).
struct FrameBuffer {
    int width = 0;
    int height = 0;
    std::vector<glm::vec3> irradiance;
    std::vector<glm::vec3> reflectance;
    std::vector<glm::vec3> normal;
    std::vector<float> depth;
    std::vector<glm::vec3> unfiltered;
    std::vector<glm::vec3> glossy;

    /// Channel bits of the planes that may hold something other than their empty value (zero;
    /// depth +inf). A plane whose bit is clear is empty everywhere, so the filter need not read
    /// it: a diffuse scene's glossy plane, a scene without mirrors' unfiltered one.
    struct LiveMask {
        std::atomic<std::uint32_t> bits{kAllChannels};
        LiveMask() = default;
        LiveMask(const LiveMask& o) : bits(o.bits.load()) {}
        LiveMask& operator=(const LiveMask& o) {
            bits = o.bits.load();
            return *this;
        }
        bool has(Channel c) const { return (bits.load(std::memory_order_relaxed) & c) != 0; }
    } live;

    /// Sizes every plane for width x height and clears it (depth +inf: no surface). Every plane
    /// counts as live: the caller may fill them directly.
    void reset(int w, int h);

    /// Makes the buffer ready for a frame of which every pixel will be scattered (a frame is
    /// composited only once all its tiles are in). Memory of the same size
    /// is kept as it is, without clearing: each pixel is overwritten by its tile, and clearing
    /// 76 bytes a pixel every frame costs the master more than filtering them. Planes no tile
    /// has sent stay empty and are neither written nor read.
    void reuse(int w, int h);

    /// Copies a tile's pixels to their places. Planes the tile did not send are empty there.
    /// Tiles of one frame may be scattered from several threads at once.
    void scatter(const Tile& tile, int n, int m, const TileChannels& channels);
};

}  // namespace igi
