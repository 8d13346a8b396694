#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include "render/Tile.h"
#include "render/TileChannels.h"

namespace igi {

/// The planes of a whole frame as the master assembles them from tile results; the input of
/// the discontinuity buffer.
struct FrameBuffer {
    int width = 0;
    int height = 0;
    std::vector<glm::vec3> irradiance;
    std::vector<glm::vec3> reflectance;
    std::vector<glm::vec3> normal;
    std::vector<float> depth;
    std::vector<glm::vec3> unfiltered;
    std::vector<glm::vec3> glossy;

    /// Sizes every plane for width x height and clears it (depth +inf: no surface).
    void reset(int w, int h);

    /// Copies a tile's pixels to their places. Planes the tile did not send are zero.
    void scatter(const Tile& tile, int n, int m, const TileChannels& channels);
};

}  // namespace igi
