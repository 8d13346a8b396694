#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "ByteReader.h"
#include "render/TileChannels.h"

namespace igi::proto {

/// A tile's channel block as it comes off the wire, validated but neither decompressed nor
/// dequantized (Quantize.h): what readTileChannels turns into floats, and what the master
/// decompresses straight into its frame (CodedFrame.h). Decompressed, the sent planes follow
/// each other in bit order, each holding its codes byte-shuffled: byte b of pixel i of plane
/// c at planeOffset(c) + b * count + i.
struct TileCodes {
    std::uint32_t count = 0;   ///< pixels
    std::uint32_t planes = 0;  ///< the planes the tile has (Channel bits)
    std::uint32_t sent = 0;    ///< of which those on the wire; the others are empty (zero, +inf)
    float irradianceScale = 0, depthMin = 0, unfilteredScale = 0, glossyScale = 0;
    std::span<const std::uint8_t> compressed;  ///< the zstd frame of the sent planes (none: empty)

    /// Bytes of the sent planes, decompressed.
    std::size_t rawSize() const;
    /// Where sent plane c starts among them.
    std::size_t planeOffset(Channel c) const;
};

/// Reads the channel block of a tile result (what writeTileChannels wrote) up to its
/// compressed planes, validating count, masks and references as readTileChannels does.
TileCodes readTileCodes(ByteReader& in);

/// Decompresses the sent planes into `out` (rawSize() bytes; nothing when none was sent).
/// Throws ProtocolError naming `what` unless the zstd frame holds exactly that many bytes.
void decompressPlanes(const TileCodes& codes, std::span<std::uint8_t> out, std::string_view what);

}  // namespace igi::proto
