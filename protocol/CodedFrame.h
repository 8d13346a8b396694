#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

#include "TileCodes.h"
#include "math/Lanes.h"
#include "render/CellOrder.h"
#include "render/FrameRow.h"
#include "render/Tile.h"

namespace igi::proto {

/// A frame as the master assembles it from tile results: each tile's planes are copied as
/// they come out of zstd, still quantized and byte-shuffled (TileCodes: 15 bytes a pixel for
/// the planes of a diffuse scene, where floats would take 52), and dequantized only when the
/// compositor reads the frame row by row (decodeRow). The frame keeps each byte plane's rows in
/// cell order (CellOrder.h), where a tile's row is one run: a tile is copied in a few dozen
/// short runs (not a store per pixel and plane), and a row is decoded from a few sequential
/// streams.
///
/// decodeRow gives bit for bit what readTileChannels, FrameBuffer::scatter and splitRow give:
/// the same tables and the same arithmetic, eight pixels at a time.
class CodedFrame {
  public:
    /// Bytes a pixel takes (every plane sent).
    static constexpr std::size_t kBytesPerPixel = 19;

    CodedFrame() = default;
    CodedFrame(CodedFrame&& o) noexcept { *this = std::move(o); }
    CodedFrame& operator=(CodedFrame&& o) noexcept;

    /// Makes the frame ready for one whose every tile (makeTiles(width, height, n, m,
    /// tileSize)) will be scattered. Memory of the same shape is kept as it is, without
    /// clearing: every tile overwrites its pixels.
    void reuse(int width, int height, int n, int m, int tileSize);

    /// Decompresses a tile's planes and copies them to their places. Throws ProtocolError
    /// naming `what`, before it writes anything, when `codes` do not have the tile's pixel count
    /// or their zstd frame is not exactly the planes it should hold. Tiles of one frame may be
    /// scattered from several threads at once.
    void scatter(const Tile& tile, const TileCodes& codes, std::string_view what = "TileResult");

    /// Copies every cell of region `region` (a tile-layout region: makeTiles' rectangle of
    /// tileSize * n by tileSize * m pixels, at any cell) from `from`, a frame of the same
    /// shape: its bytes and its tiles' references, as if its tiles had been scattered here.
    /// Adaptive tiles fill the regions a frame leaves out with their last rendered cells, so
    /// that the discontinuity buffer beside them reads the same whoever rendered what.
    void copyRegion(const CodedFrame& from, const Tile& region);

    /// Row y, dequantized, in order(). Planes a tile did not send are empty there (zero, depth
    /// +inf); the glossy arrays are left as they are unless live(kGlossy).
    void decodeRow(int y, FrameRow& row, lanes::Isa isa = lanes::bestIsa()) const;

    int width() const { return width_; }
    int height() const { return height_; }
    const CellOrder& order() const { return order_; }
    /// Whether some tile has sent plane c since the memory was laid out.
    bool live(Channel c) const { return (live_.load(std::memory_order_relaxed) & c) != 0; }

  private:
    /// What a tile sent besides its codes: which planes, and their references (1 when none).
    struct TileRecord {
        std::uint32_t sent = 0;
        float irradiance = 1, depth = 1, unfiltered = 1, glossy = 1;
    };
    std::size_t slot(int kx, int ky, int regionX, int regionY) const;
    /// Row y of byte plane b (planes in wire order: irradiance's four bytes, reflectance's
    /// three, ...), in cell order.
    std::uint8_t* bytes(int y, int b) const {
        return bytes_.get() + std::size_t(b) * planeStride_ + std::size_t(y) * planeBytes_;
    }
    template <bool Avx2>
    IGI_LANES void decodeRowBody(int y, FrameRow& row) const;
    void decodeRowBaseline(int y, FrameRow& row) const;
#if IGI_HAS_AVX2_TARGET
    IGI_AVX2 void decodeRowAvx2(int y, FrameRow& row) const;
#endif

    int width_ = 0, height_ = 0, n_ = 1, m_ = 1, tileSize_ = 1, regionsX_ = 0, regionsY_ = 0;
    CellOrder order_;
    std::size_t planeBytes_ = 0;             ///< a row of one byte plane
    std::size_t planeStride_ = 0;            ///< a whole byte plane, with padding
    std::unique_ptr<std::uint8_t[]> bytes_;  ///< byte plane by byte plane
    std::vector<TileRecord> records_;        ///< per tile
    std::atomic<std::uint32_t> live_{0};
};

}  // namespace igi::proto
