#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace igi::proto {

/// One zstd frame of `data` at `level` (the frame header records the content size). Small inputs
/// (tiles) reuse a compression context kept per thread; the bytes are those of ZSTD_compress.
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
/// The same into `out`, whose storage is reused (a tile decoder's buffer): on success `out`
/// holds exactly the `expectedSize` bytes of content. Content up to 1 MiB (a tile) is
/// decompressed in one call with a context kept per thread into `out` sized up front, as the
/// first 1 MiB step would be; larger content grows `out` step by step as above.
void zstdDecompressExactInto(std::span<const std::uint8_t> frame, std::size_t expectedSize,
                             std::string_view what, std::vector<std::uint8_t>& out);
/// The same into `out`, memory the caller has set aside for exactly out.size() bytes of
/// content (a tile's place in the master's frame), in one call with a context kept per thread.
void zstdDecompressExactTo(std::span<const std::uint8_t> frame, std::span<std::uint8_t> out,
                           std::string_view what);

}  // namespace igi::proto
