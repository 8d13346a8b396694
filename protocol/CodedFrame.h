#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "TileCodes.h"
#include "math/Lanes.h"
#include "render/CellOrder.h"
#include "render/FrameRow.h"
#include "render/Tile.h"

namespace igi::proto {

/// A frame as the master assembles it from tile results: each tile's planes are copied as
/// they come off the wire, still quantized (TileCodes: 15 bytes a pixel for the planes of a
/// diffuse scene, where floats would take 52), and dequantized only when the compositor reads
/// the frame row by row (decodeRow). The rows are kept in cell order (CellOrder.h), where each
/// row of a tile is one run of bytes: scattering a tile is a few dozen copies, not a store per
/// pixel and plane, and a frame is small enough to stay in the cache until it is filtered.
///
/// decodeRow gives bit for bit what readTileChannels, FrameBuffer::scatter and splitRow give:
/// the same tables and the same arithmetic, eight pixels at a time.
class CodedFrame {
  public:
    /// Bytes a pixel takes when every plane is live.
    static constexpr std::size_t kBytesPerPixel = 19;

    CodedFrame() = default;
    CodedFrame(CodedFrame&& o) noexcept { *this = std::move(o); }
    CodedFrame& operator=(CodedFrame&& o) noexcept;

    /// Makes the frame ready for one whose every tile (makeTiles(width, height, n, m,
    /// tileSize)) will be scattered. Memory of the same shape is kept as it is, without
    /// clearing: each tile overwrites its pixels, in every plane that any tile has sent.
    void reuse(int width, int height, int n, int m, int tileSize);

    /// Copies a tile's codes to their places; planes it did not send are empty there. Throws
    /// ProtocolError when `codes` do not have the tile's pixel count. Tiles of one frame may be
    /// scattered from several threads at once.
    void scatter(const Tile& tile, const TileCodes& codes);

    /// Row y, dequantized, in order(). A plane no tile has sent holds its empty value (zero,
    /// depth +inf), except glossy, which is left as it is unless live(kGlossy).
    void decodeRow(int y, FrameRow& row, lanes::Isa isa = lanes::bestIsa()) const;

    int width() const { return width_; }
    int height() const { return height_; }
    const CellOrder& order() const { return order_; }
    /// Whether some tile has sent plane c since the memory was laid out.
    bool live(Channel c) const { return (live_.load(std::memory_order_acquire) & c) != 0; }

  private:
    /// The references a tile sent with its planes (1 for a plane it did not send).
    struct Scales {
        float irradiance = 1, depth = 1, unfiltered = 1, glossy = 1;
    };
    std::size_t slot(int kx, int ky, int regionX, int regionY) const;
    std::uint8_t* bytePlane(int b) { return bytes_.get() + std::size_t(b) * planeStride_; }
    const std::uint8_t* bytePlane(int b) const {
        return bytes_.get() + std::size_t(b) * planeStride_;
    }
    /// Sets plane c live, filling it with its empty code first (once per plane and layout).
    void bringToLife(Channel c);
    IGI_LANES void decodeRowBody(int y, FrameRow& row) const;
    void decodeRowBaseline(int y, FrameRow& row) const;
#if IGI_HAS_AVX2_TARGET
    IGI_AVX2 void decodeRowAvx2(int y, FrameRow& row) const;
#endif

    int width_ = 0, height_ = 0, n_ = 1, m_ = 1, tileSize_ = 1, regionsX_ = 0, regionsY_ = 0;
    CellOrder order_;
    std::size_t planeStride_ = 0;
    std::unique_ptr<std::uint8_t[]> bytes_;  ///< the byte planes, uninitialized until live
    std::vector<Scales> scales_;             ///< per tile
    std::atomic<std::uint32_t> live_{0};
};

}  // namespace igi::proto
