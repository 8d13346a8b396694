#pragma once

#include <cstdint>
#include <vector>

#include "render/CellOrder.h"
#include "render/Tile.h"

namespace igi {

/// The regions of a tile layout (makeTiles: (tileSize * n) x (tileSize * m) pixels, each
/// rendered by its n * m tiles, one per interleaving cell), and which of them a frame renders:
/// adaptive tiles leave out the regions whose estimated error is below the target. A region is
/// rendered or left out whole, with all its cells, so that the discontinuity buffer and the
/// accumulation see every cell of a pixel's neighbourhood from the same frames.
class TileRegions {
  public:
    TileRegions() = default;
    /// Every region rendered.
    TileRegions(int width, int height, int n, int m, int tileSize);

    int count() const { return int(rendered_.size()); }
    int columns() const { return columns_; }
    /// The region tile `t` renders a cell of.
    int regionOf(const Tile& t) const {
        return (t.y0 / regionHeight_) * columns_ + t.x0 / regionWidth_;
    }
    int regionAt(int x, int y) const { return (y / regionHeight_) * columns_ + x / regionWidth_; }
    /// The tile of the layout whose cells are region r's (cell (0, 0)): its rectangle.
    Tile rectangle(int region) const;

    bool rendered(int region) const { return rendered_[std::size_t(region)] != 0; }
    void setRendered(int region, bool rendered) { rendered_[std::size_t(region)] = rendered; }
    /// Whether every region is rendered.
    bool all() const;
    int renderedCount() const;

    /// Row y as the accumulation reads it (RowAccumulator::addRow's `rendered`): 1 where the
    /// pixel's region is rendered, 0 where not, in `order` (its width, then `padding` more
    /// entries of 1).
    void rowMask(int y, const CellOrder& order, float* out, std::size_t padding) const;

    bool operator==(const TileRegions&) const = default;

  private:
    int width_ = 0, height_ = 0, regionWidth_ = 1, regionHeight_ = 1, columns_ = 0;
    std::vector<std::uint8_t> rendered_;
};

}  // namespace igi
