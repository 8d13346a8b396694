#pragma once

#include <cstdint>

#include "ByteReader.h"
#include "ByteWriter.h"
#include "render/TileChannels.h"

namespace igi::proto {

/// Most pixels a tile result may carry (a 1024 x 1024 tile).
constexpr std::uint32_t kMaxTilePixels = 1u << 20;

/// Bytes per pixel of each plane on the wire before compression.
constexpr std::uint32_t kIrradianceBytes = 4;   // shared-exponent RGB
constexpr std::uint32_t kReflectanceBytes = 3;  // 3 x sRGB u8
constexpr std::uint32_t kNormalBytes = 2;       // octahedral 2 x u8
constexpr std::uint32_t kDepthBytes = 2;        // log2 u16
constexpr std::uint32_t kUnfilteredBytes = 4;   // shared-exponent RGB
constexpr std::uint32_t kGlossyBytes = 4;       // shared-exponent RGB
std::uint32_t bytesPerPixel(std::uint32_t mask);

/// The zstd level tiles are compressed at. Negative: literals are stored raw (no Huffman
/// stage), and zstd decodes a third faster for a wire about 1 % larger: igi-codec-bench at
/// level 1 and -1 gave zstd 8.4 -> 5.7 ns/pixel and 4.08 -> 4.13 bytes/pixel, and the default
/// scene end to end went 4.42 -> 4.45 bytes/pixel (docs/PERFORMANCE.md, section 5, builds
/// db25edc and d261781). zstd decoding was the largest cost of the master's compositing thread
/// after the filter. Any level decodes alike.
constexpr int kTileZstdLevel = -1;

/// Quantizes the planes of `channels`, lays them out planar (and, within a plane, one byte of
/// each pixel after the other, which zstd compresses much better), and appends them
/// zstd-compressed (kTileZstdLevel). Planes that quantize to all zeros (depth: all +inf) are left
/// out. Throws ProtocolError when a plane's size is not `count` or `count` exceeds kMaxTilePixels.
void writeTileChannels(ByteWriter& out, const TileChannels& channels);

/// Reads what writeTileChannels wrote. Validates the masks, the pixel count, the scales and
/// the decompressed size before allocating; planes left out come back zero (depth +inf).
TileChannels readTileChannels(ByteReader& in);

}  // namespace igi::proto
