#pragma once

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "ByteWriter.h"
#include "ChannelCodec.h"
#include "render/Tile.h"
#include "render/TileChannels.h"

namespace igi::proto::test {

/// Tile results of a frame as hostile to the master's decoder and filter as valid data can be:
/// surfaces that break in depth and normal, misses (+inf and NaN depth), pixels without a
/// normal, negative and NaN values (which quantize to zero), planes left out of some tiles,
/// and references far outside the range of the fast path (CodedFrame.h): a tile whose
/// irradiance is all below 1e-30 (with pixels a billion times darker still) or near the
/// largest float.
struct RandomTiles {
    std::uint32_t planes = kIrradiance | kReflectance | kNormal | kDepth | kUnfiltered;
    bool extremeScales = true;

    TileChannels channels(const Tile& t, int n, int m, std::mt19937& rng) const {
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        TileChannels c;
        // Some tiles leave planes out (a mirror's unfiltered radiance only here and there).
        std::uint32_t mask = planes;
        if (u(rng) < 0.3f) mask &= ~kUnfiltered;
        if (u(rng) < 0.2f) mask &= ~kGlossy;
        c.resize(t.pixelCount(n, m), mask);
        const float scale = !extremeScales  ? 1.0f
                            : u(rng) < 0.1f ? 1e-32f
                            : u(rng) < 0.1f ? 1e37f
                                            : 1.0f;
        const float surface = u(rng) < 0.5f ? 2.0f : 2.06f;
        // Half the tiles a flat albedo (the same codes pixel after pixel), half a texture.
        const bool flat = u(rng) < 0.5f;
        const glm::vec3 albedo(u(rng), u(rng), u(rng));
        for (int i = 0; i < c.count; ++i) {
            const float r = u(rng);
            if (!c.depth.empty())
                c.depth[i] = r < 0.04f   ? std::numeric_limits<float>::infinity()
                             : r < 0.05f ? std::numeric_limits<float>::quiet_NaN()
                                         : surface + (u(rng) < 0.3f ? 0.2f : 0.01f) * u(rng);
            if (!c.normal.empty()) {
                c.normal[i] = u(rng) < 0.8f ? glm::vec3(0, 0, 1)
                                            : glm::normalize(glm::vec3(u(rng), u(rng), 1.0f));
                if (u(rng) < 0.03f) c.normal[i] = glm::vec3(0.0f);
            }
            if (!c.irradiance.empty()) {
                // Now and then a pixel far darker than the tile's brightest: small exponents.
                const float dark = u(rng) < 0.1f ? 1e-9f : 1.0f;
                c.irradiance[i] = glm::vec3(u(rng), u(rng), u(rng)) * 3.0f * dark * scale;
                if (u(rng) < 0.02f) c.irradiance[i].x = -1.0f;
            }
            if (!c.reflectance.empty())
                c.reflectance[i] = flat ? albedo : glm::vec3(u(rng), u(rng), u(rng));
            if (!c.unfiltered.empty())
                c.unfiltered[i] = u(rng) < 0.2f ? glm::vec3(u(rng)) : glm::vec3(0.0f);
            if (!c.glossy.empty())
                c.glossy[i] =
                    u(rng) < 0.5f ? glm::vec3(u(rng), u(rng), u(rng)) * 0.5f : glm::vec3(0.0f);
        }
        return c;
    }

    /// Every tile of the layout, encoded as a client sends its planes.
    std::vector<std::vector<std::uint8_t>> encoded(const std::vector<Tile>& tiles, int n, int m,
                                                   std::mt19937& rng) const {
        std::vector<std::vector<std::uint8_t>> wire;
        for (const Tile& t : tiles) {
            std::vector<std::uint8_t> bytes;
            ByteWriter out(bytes);
            writeTileChannels(out, channels(t, n, m, rng));
            wire.push_back(std::move(bytes));
        }
        return wire;
    }
};

}  // namespace igi::proto::test
