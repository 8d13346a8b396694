#pragma once

#include <cstdint>
#include <vector>

namespace igi {

/// A unit of work: the pixels of one interleaving cell (kx, ky) inside an image region. The
/// region's corner (x0, y0) is a multiple of the interleaving size n x m, so pixel (x, y) of the
/// region belongs to the tile when (x - x0) % n == kx and (y - y0) % m == ky, and all its pixels
/// use the same sets P_k and C_k, k = ky * n + kx.
struct Tile {
    int x0 = 0, y0 = 0, width = 0, height = 0;
    int kx = 0, ky = 0;

    int setIndex(int n) const { return ky * n + kx; }
    /// Columns and rows of the tile's strided pixel grid.
    int columns(int n) const { return width > kx ? (width - kx + n - 1) / n : 0; }
    int rows(int m) const { return height > ky ? (height - ky + m - 1) / m : 0; }
    int pixelCount(int n, int m) const { return columns(n) * rows(m); }

    /// Image coordinates of the pixel in column c, row r of the tile's strided grid.
    int columnX(int c, int n) const { return x0 + kx + c * n; }
    int rowY(int r, int m) const { return y0 + ky + r * m; }
    /// Image coordinates of the tile's i-th pixel (row-major in the strided grid).
    int pixelX(int i, int n) const { return columnX(i % columns(n), n); }
    int pixelY(int i, int n, int m) const { return rowY(i / columns(n), m); }

    bool operator==(const Tile&) const = default;
};

/// Cuts an image into tiles: regions of (tileSize * n) x (tileSize * m) pixels, each split into
/// its n * m interleaving cells. Tiles of one k are listed together, k by k, so that handing
/// them out in order keeps a client on one set. Cells with no pixel (tiny images) are skipped.
std::vector<Tile> makeTiles(int width, int height, int n, int m, int tileSize);

}  // namespace igi
