#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace igi::proto {

/// One zstd frame of `data` at `level` (the frame header records the content size).
std::vector<std::uint8_t> zstdCompress(std::span<const std::uint8_t> data, int level);
/// The same frame, appended to `out` (saves a copy of a large scene).
void zstdCompressAppend(std::span<const std::uint8_t> data, int level,
                        std::vector<std::uint8_t>& out);

/// Decompresses untrusted bytes that must be exactly one zstd frame whose header declares
/// exactly `expectedSize` bytes of content (the caller has already bounded `expectedSize`).
/// The output grows only as content is actually produced and never beyond `expectedSize`, so a
/// frame that lies about its size (a "zstd bomb") is refused instead of being allocated.
/// Throws ProtocolError naming `what` on any mismatch or corruption.
std::vector<std::uint8_t> zstdDecompressExact(std::span<const std::uint8_t> frame,
                                              std::size_t expectedSize, std::string_view what);

}  // namespace igi::proto
