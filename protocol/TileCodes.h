#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "ByteReader.h"
#include "render/TileChannels.h"

namespace igi::proto {

/// A tile's planes as they come off the wire, decompressed but not dequantized (Quantize.h):
/// what readTileChannels turns into floats and what the master copies into its frame as they
/// are (CodedFrame.h). Each sent plane holds its codes byte-shuffled: byte b of pixel i at
/// bytes(plane)[b * count + i].
struct TileCodes {
    std::uint32_t count = 0;   ///< pixels
    std::uint32_t planes = 0;  ///< the planes the tile has (Channel bits)
    std::uint32_t sent = 0;    ///< of which those on the wire; the others are empty (zero, +inf)
    float irradianceScale = 0, depthMin = 0, unfilteredScale = 0, glossyScale = 0;
    std::span<const std::uint8_t> raw;  ///< every sent plane, in bit order

    /// The codes of a sent plane (null when `c` was not sent).
    const std::uint8_t* bytes(Channel c) const;
};

/// Reads the channel block of a tile result (what writeTileChannels wrote), validating it as
/// readTileChannels does before anything is allocated, and decompresses the planes into `raw`
/// (reused storage), which the result points into.
TileCodes readTileCodes(ByteReader& in, std::vector<std::uint8_t>& raw);

}  // namespace igi::proto
