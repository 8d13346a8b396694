#include "render/RowAccumulator.h"

#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "render/Accumulator.h"

namespace igi {
namespace {

std::vector<lanes::Isa> isas() {
    std::vector<lanes::Isa> v = {lanes::Isa::kBaseline};
    if (lanes::hasAvx2()) v.push_back(lanes::Isa::kAvx2);
    return v;
}

/// A frame's filtered and unfiltered images: noisy, with a region where the two differ by a
/// bias (where the progressive filter withdraws the blur), now and then a huge value.
void randomImages(int w, int h, std::mt19937& rng, std::vector<glm::vec3>& filtered,
                  std::vector<glm::vec3>& unfiltered) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    filtered.resize(std::size_t(w) * h);
    unfiltered.resize(filtered.size());
    for (std::size_t p = 0; p < filtered.size(); ++p) {
        const int x = int(p % std::size_t(w));
        const glm::vec3 base(u(rng), u(rng), u(rng));
        unfiltered[p] = base * (0.5f + u(rng)) * (u(rng) < 0.01f ? 1e6f : 1.0f);
        filtered[p] = base * (x < w / 2 ? 1.0f : 0.6f + 0.1f * u(rng));
    }
}

// The compositor's accumulation against Accumulator, bit for bit, frame after frame: row by
// row in every cell order, pooled windows of several shapes (and none), with and without the
// progressive filter, means read after each frame (as the compositor does, before endFrame with
// the frame count after it, and after it).
TEST(RowAccumulator, EqualsAccumulatorBitForBit) {
    const int sizes[][2] = {{17, 11}, {5, 5}, {2, 7}, {64, 9}, {33, 3}};
    const int windows[][2] = {{3, 3}, {1, 1}, {4, 2}, {2, 5}};
    std::mt19937 rng(3);
    for (const auto& size : sizes)
        for (const auto& window : windows)
            for (const bool withdraw : {true, false})
                for (int cells : {1, 3, 4})
                    for (const lanes::Isa isa : isas()) {
                        const int w = size[0], h = size[1];
                        const CellOrder order(w, cells);
                        Accumulator reference;
                        reference.reset(w, h, withdraw, window[0], window[1]);
                        RowAccumulator rows;
                        rows.reset(order, h, withdraw, window[0], window[1]);
                        std::vector<glm::vec3> filtered, unfiltered, expected(std::size_t(w) * h),
                            got(expected.size());
                        std::vector<std::vector<double>> variance(
                            std::size_t(h), std::vector<double>(rows.varianceEntries()));
                        ShadedRow shaded;
                        shaded.resize(w);
                        for (int frame = 0; frame < 5; ++frame) {
                            randomImages(w, h, rng, filtered, unfiltered);
                            reference.addRows(filtered, unfiltered, 0, h);
                            reference.endFrame();
                            reference.meanRows(expected, 0, h);
                            for (int y = 0; y < h; ++y) {
                                for (int x = 0; x < w; ++x) {
                                    const std::size_t p = std::size_t(y) * w + x;
                                    const int i = order.position(x);
                                    for (int c = 0; c < 3; ++c) {
                                        shaded[ShadedRow::kFr + c][i] = filtered[p][c];
                                        shaded[ShadedRow::kUr + c][i] = unfiltered[p][c];
                                    }
                                }
                                rows.addRow(y, shaded, variance[std::size_t(y)].data(), isa);
                            }
                            const int after = rows.frames() + 1;
                            for (int pass = 0; pass < 2; ++pass) {  // before and after endFrame
                                if (pass == 1) {
                                    rows.endFrame();
                                    // Recomputed from the sums: what adding the rows gave.
                                    for (int y = 0; y < h; ++y)
                                        rows.varianceRow(y, after, variance[std::size_t(y)].data(),
                                                         isa);
                                }
                                for (int y = 0; y < h; ++y) {
                                    const auto [first, last] = rows.meanWindow(y);
                                    std::vector<const double*> window;
                                    for (int k = first; k < last; ++k)
                                        window.push_back(variance[std::size_t(k)].data());
                                    rows.meanRow(y, after, window.data(),
                                                 got.data() + std::size_t(y) * w, isa);
                                }
                                for (std::size_t p = 0; p < got.size(); ++p)
                                    ASSERT_EQ(std::memcmp(&got[p], &expected[p], sizeof(got[p])), 0)
                                        << w << "x" << h << " window " << window[0] << "x"
                                        << window[1] << " withdraw " << withdraw << " cells "
                                        << cells << " frame " << frame << " pass " << pass
                                        << " pixel " << p << ": " << got[p].x << " vs "
                                        << expected[p].x;
                            }
                        }
                    }
}

}  // namespace
}  // namespace igi
