#include "render/Tile.h"

#include <vector>

#include <gtest/gtest.h>

namespace igi {
namespace {

// Every pixel belongs to exactly one tile, and the tile's k is the pixel's interleaving cell.
void expectExactCover(int width, int height, int n, int m, int tileSize) {
    std::vector<int> covered(std::size_t(width) * height, 0);
    for (const Tile& t : makeTiles(width, height, n, m, tileSize)) {
        EXPECT_EQ(t.x0 % n, 0);
        EXPECT_EQ(t.y0 % m, 0);
        ASSERT_GT(t.pixelCount(n, m), 0);
        for (int i = 0; i < t.pixelCount(n, m); ++i) {
            const int x = t.pixelX(i, n), y = t.pixelY(i, n, m);
            ASSERT_GE(x, 0);
            ASSERT_LT(x, width);
            ASSERT_GE(y, 0);
            ASSERT_LT(y, height);
            EXPECT_EQ(x % n, t.kx);
            EXPECT_EQ(y % m, t.ky);
            ++covered[std::size_t(y) * width + x];
        }
    }
    for (int c : covered) ASSERT_EQ(c, 1) << width << "x" << height << " " << n << "x" << m;
}

TEST(Tile, TilesCoverEveryPixelOnce) {
    expectExactCover(640, 480, 3, 3, 32);
    expectExactCover(641, 479, 3, 3, 32);
    expectExactCover(37, 23, 4, 2, 5);
    expectExactCover(1, 1, 3, 3, 32);
    expectExactCover(2, 1, 3, 3, 1);
    expectExactCover(100, 100, 1, 1, 7);
}

TEST(Tile, TilesOfOneKAreListedTogether) {
    const auto tiles = makeTiles(200, 100, 3, 3, 8);
    int changes = 0;
    for (std::size_t i = 1; i < tiles.size(); ++i)
        changes += tiles[i].setIndex(3) != tiles[i - 1].setIndex(3);
    EXPECT_EQ(changes, 8);  // nine runs, one per k
}

}  // namespace
}  // namespace igi
