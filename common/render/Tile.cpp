#include "render/Tile.h"

#include <algorithm>

namespace igi {

std::vector<Tile> makeTiles(int width, int height, int n, int m, int tileSize) {
    const int regionW = tileSize * n, regionH = tileSize * m;
    std::vector<Tile> tiles;
    for (int ky = 0; ky < m; ++ky) {
        for (int kx = 0; kx < n; ++kx) {
            for (int y0 = 0; y0 < height; y0 += regionH) {
                for (int x0 = 0; x0 < width; x0 += regionW) {
                    Tile t{x0, y0, std::min(regionW, width - x0), std::min(regionH, height - y0),
                           kx, ky};
                    if (t.pixelCount(n, m) > 0) tiles.push_back(t);
                }
            }
        }
    }
    return tiles;
}

}  // namespace igi
