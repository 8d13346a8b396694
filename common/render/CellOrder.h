#pragma once

#include <vector>

#include <glm/vec3.hpp>

namespace igi {

/// The order in which the master keeps the columns of a frame row: grouped by interleaving
/// column, all x with x % n == 0 first (left to right), then x % n == 1, ... Tiles are strided
/// grids (Tile.h), so a tile's row is one contiguous run of positions here, copied in one piece
/// instead of one pixel in n; and the neighbour at x + dx of eight consecutive pixels of one
/// cell is eight consecutive positions too, which the filter's lanes load at once.
class CellOrder {
  public:
    CellOrder() = default;
    /// `cells` = n, the interleaving width (1: image order).
    CellOrder(int width, int cells);

    int width() const { return width_; }
    int cells() const { return cells_; }
    /// Position of x = kx, the first of cell column kx.
    int start(int kx) const { return start_[static_cast<std::size_t>(kx)]; }
    /// Columns x < width with x % n == kx.
    int count(int kx) const { return start(kx + 1) - start(kx); }
    int position(int x) const { return start(x % cells_) + x / cells_; }
    /// position(x + dx) - position(x) for any x with x % n == kx (x + dx inside the row).
    int offset(int kx, int dx) const;

  private:
    int width_ = 0;
    int cells_ = 1;
    std::vector<int> start_{0, 0};  ///< cells + 1 entries
};

/// Writes a row given in cell order as three arrays (r, g, b) to `out`, an image row of
/// glm::vec3 in image order.
void toImageOrder(const CellOrder& order, const float* r, const float* g, const float* b,
                  glm::vec3* out);
/// The same, streamed past the cache (an image written whole every frame and rarely read soon
/// after: the stores need not fetch its lines first). Call streamedStoresDone() before another
/// thread reads it.
void toImageOrderStreamed(const CellOrder& order, const float* r, const float* g, const float* b,
                          glm::vec3* out);
void streamedStoresDone();

}  // namespace igi
