#include "render/TileRegions.h"

#include <gtest/gtest.h>

namespace igi {
namespace {

// Every tile of a layout lies in the region regionOf names, the n * m tiles of a region (its
// cells) share it, and the regions cover the image once.
TEST(TileRegions, EveryTileLiesInItsRegion) {
    const int w = 70, h = 45, n = 3, m = 2, tileSize = 4;
    const TileRegions regions(w, h, n, m, tileSize);
    std::vector<int> cells(std::size_t(regions.count()), 0);
    for (const Tile& t : makeTiles(w, h, n, m, tileSize)) {
        const int r = regions.regionOf(t);
        ASSERT_GE(r, 0);
        ASSERT_LT(r, regions.count());
        ++cells[std::size_t(r)];
        const Tile rect = regions.rectangle(r);
        EXPECT_EQ(rect.x0, t.x0);
        EXPECT_EQ(rect.y0, t.y0);
        EXPECT_EQ(rect.width, t.width);
        EXPECT_EQ(rect.height, t.height);
        for (int i = 0; i < t.pixelCount(n, m); ++i)
            EXPECT_EQ(regions.regionAt(t.pixelX(i, n), t.pixelY(i, n, m)), r);
    }
    for (const int c : cells) EXPECT_EQ(c, n * m);
}

// The accumulation's mask: 0 exactly at the pixels of regions left out, in cell order, and
// the padding 1.
TEST(TileRegions, RowMaskMarksThePixelsOfRegionsLeftOut) {
    const int w = 30, h = 20, n = 2, m = 2, tileSize = 3;
    TileRegions regions(w, h, n, m, tileSize);
    EXPECT_TRUE(regions.all());
    regions.setRendered(1, false);
    regions.setRendered(regions.columns() + 2, false);
    EXPECT_FALSE(regions.all());
    EXPECT_EQ(regions.renderedCount(), regions.count() - 2);
    const CellOrder order(w, n);
    std::vector<float> mask(std::size_t(w) + 8, -1.0f);
    for (int y = 0; y < h; ++y) {
        regions.rowMask(y, order, mask.data(), 8);
        for (int x = 0; x < w; ++x)
            EXPECT_EQ(mask[std::size_t(order.position(x))],
                      regions.rendered(regions.regionAt(x, y)) ? 1.0f : 0.0f)
                << x << ", " << y;
        for (int k = 0; k < 8; ++k) EXPECT_EQ(mask[std::size_t(w + k)], 1.0f);
    }
}

}  // namespace
}  // namespace igi
