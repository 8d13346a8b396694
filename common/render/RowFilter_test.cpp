#include "render/RowFilter.h"

#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "render/TestFrames.h"

namespace igi {
namespace {

std::vector<lanes::Isa> isas() {
    std::vector<lanes::Isa> v = {lanes::Isa::kBaseline};
    if (lanes::hasAvx2()) v.push_back(lanes::Isa::kAvx2);
    return v;
}

/// Filters every row of `f` with filterRow on rows split in `order`, back in image order.
void filterFrame(const FrameBuffer& f, const CellOrder& order, DiscontinuityFilterSettings s,
                 lanes::Isa isa, std::vector<glm::vec3>& filtered,
                 std::vector<glm::vec3>& unfiltered) {
    std::vector<FrameRow> rows(std::size_t(f.height));
    for (int y = 0; y < f.height; ++y) splitRow(f, y, order, rows[std::size_t(y)]);
    filtered.assign(f.depth.size(), glm::vec3(-1.0f));
    unfiltered.assign(f.depth.size(), glm::vec3(-1.0f));
    ShadedRow out;
    for (int y = 0; y < f.height; ++y) {
        FilterWindow w;
        const int y0 = filterWindowStart(y, s.sizeY, f.height);
        w.count = std::min(f.height, y0 + s.sizeY) - y0;
        for (int k = 0; k < w.count; ++k) w.rows[k] = &rows[std::size_t(y0 + k)];
        w.centre = &rows[std::size_t(y)];
        filterRow(w, order, s, f.live.has(kGlossy), true, out, isa);
        glm::vec3* row = filtered.data() + std::size_t(y) * f.width;
        toImageOrder(order, out[ShadedRow::kFr], out[ShadedRow::kFg], out[ShadedRow::kFb], row);
        row = unfiltered.data() + std::size_t(y) * f.width;
        toImageOrder(order, out[ShadedRow::kUr], out[ShadedRow::kUg], out[ShadedRow::kUb], row);
    }
}

// The eight-wide kernel, in both instruction sets and with the columns in every cell order the
// master may keep them (one to five interleaving columns), against the one-pixel reference bit
// for bit: borders, windows of every shape, misses (+inf, -inf and NaN depth), pixels without a
// normal, a glossy plane live or not, and widths that leave every remainder of eight lanes.
TEST(RowFilter, EqualsTheOnePixelReferenceInEveryCellOrder) {
    const int sizes[][2] = {{17, 11}, {5, 5}, {2, 7}, {64, 9}, {45, 6}, {103, 4}};
    const int windows[][2] = {{3, 3}, {1, 1}, {4, 2}, {5, 3}, {2, 5}, {7, 1}};
    std::uint32_t seed = 11;
    for (const auto& size : sizes)
        for (const auto& window : windows)
            for (int cells = 1; cells <= 5; ++cells)
                for (const lanes::Isa isa : isas()) {
                    FrameBuffer f = test::randomFrame(size[0], size[1], seed++);
                    if (seed % 2) {  // no glossy plane: zeros, and not read
                        std::fill(f.glossy.begin(), f.glossy.end(), glm::vec3(0.0f));
                        f.live.bits = kAllChannels & ~kGlossy;
                    }
                    const DiscontinuityFilterSettings s{window[0], window[1], 0.05f, 0.9f};
                    const auto expected = test::referenceFilter(f, s);
                    std::vector<glm::vec3> bare(f.depth.size()), filtered, unfiltered;
                    compositeUnfilteredRows(f, 0, f.height, bare);
                    filterFrame(f, CellOrder(f.width, cells), s, isa, filtered, unfiltered);
                    for (std::size_t p = 0; p < filtered.size(); ++p) {
                        ASSERT_EQ(std::memcmp(&filtered[p], &expected[p], sizeof(glm::vec3)), 0)
                            << size[0] << "x" << size[1] << " window " << window[0] << "x"
                            << window[1] << " cells " << cells << " isa " << int(isa) << " pixel "
                            << p << ": " << filtered[p].x << " vs " << expected[p].x;
                        ASSERT_EQ(std::memcmp(&unfiltered[p], &bare[p], sizeof(glm::vec3)), 0)
                            << "unfiltered pixel " << p;
                    }
                }
}

// Cell order keeps every pixel once, each interleaving column's pixels together and in order.
TEST(CellOrder, GroupsColumnsByCellAndNamesNeighbours) {
    for (int width : {1, 2, 7, 9, 10, 64}) {
        for (int cells = 1; cells <= 5; ++cells) {
            const CellOrder o(width, cells);
            std::vector<int> seen(std::size_t(width), 0);
            for (int x = 0; x < width; ++x) {
                const int p = o.position(x);
                ASSERT_GE(p, 0);
                ASSERT_LT(p, width);
                ++seen[std::size_t(p)];
                ASSERT_EQ(p, o.start(x % cells) + x / cells);
                for (int dx = -6; dx <= 6; ++dx) {
                    if (x + dx < 0 || x + dx >= width) continue;
                    ASSERT_EQ(o.position(x + dx), p + o.offset(x % cells, dx))
                        << width << " " << cells << " " << x << " " << dx;
                }
            }
            for (int v : seen) ASSERT_EQ(v, 1);
            int total = 0;
            for (int kx = 0; kx < cells; ++kx) total += o.count(kx);
            EXPECT_EQ(total, width);
        }
    }
}

}  // namespace
}  // namespace igi
