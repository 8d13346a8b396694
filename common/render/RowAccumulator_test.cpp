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
                        // Asked for, so that estimating the error is shown not to move a bit.
                        std::vector<float> errors(static_cast<std::size_t>(w));
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
                                                 got.data() + std::size_t(y) * w, errors.data(),
                                                 isa);
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

/// Adds one frame of `filtered` and `unfiltered` (image order, w x h) to `rows` and returns
/// the mean over the image of the error meanRow estimates after it.
double addAndEstimate(RowAccumulator& rows, const CellOrder& order, int w, int h,
                      const std::vector<glm::vec3>& filtered,
                      const std::vector<glm::vec3>& unfiltered) {
    std::vector<std::vector<double>> variance(std::size_t(h),
                                              std::vector<double>(rows.varianceEntries()));
    ShadedRow shaded;
    shaded.resize(w);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const std::size_t p = std::size_t(y) * w + x;
            for (int c = 0; c < 3; ++c) {
                shaded[ShadedRow::kFr + c][order.position(x)] = filtered[p][c];
                shaded[ShadedRow::kUr + c][order.position(x)] = unfiltered[p][c];
            }
        }
        rows.addRow(y, shaded, variance[std::size_t(y)].data());
    }
    rows.endFrame();
    std::vector<glm::vec3> mean(static_cast<std::size_t>(w));
    std::vector<float> error(static_cast<std::size_t>(w));
    double sum = 0;
    for (int y = 0; y < h; ++y) {
        const auto [first, last] = rows.meanWindow(y);
        std::vector<const double*> window;
        for (int k = first; k < last; ++k) window.push_back(variance[std::size_t(k)].data());
        rows.meanRow(y, rows.frames(), window.data(), mean.data(), error.data());
        for (const float e : error) sum += e;
    }
    return sum / (double(w) * h);
}

// A constant image plus Gaussian noise of a known spread: after n frames the mean's relMSE is
// sigma^2 / n / (c^2 + 0.01) per channel, and the estimate from the two half-means must find
// it within a few per cent (its own noise over 64 x 64 x 3 values is about 1.3 %), at even and
// odd n, where the filtered frames are shown (no bias between the planes: w = 1) and where the
// progressive filter withdraws the blur (a bias between them: the noisier unfiltered mean is
// shown).
TEST(RowAccumulator, EstimatesTheRelMseOfNoiseOfAKnownSpread) {
    const int w = 64, h = 64;
    const glm::vec3 level(0.5f, 1.0f, 2.0f);
    for (const bool withdraw : {false, true})
        for (const bool biased : {false, true}) {
            if (biased && !withdraw) continue;
            std::mt19937 rng(7);
            std::normal_distribution<float> noise(0.0f, 1.0f);
            const float sigmaF = 0.05f, sigmaU = 0.15f;
            // Without a bias, the filtered frames are shown; with one, the unfiltered ones, 5
            // brighter (a blur bias so far beyond the noise that the filtered mean's weight,
            // t^2 s^2 / D^2, is below 0.003 from four frames on).
            const glm::vec3 shownLevel = biased ? level + 5.0f : level;
            const float shownSigma = biased ? sigmaU : sigmaF;
            const CellOrder order(w, 3);
            RowAccumulator rows;
            rows.reset(order, h, withdraw, 3, 3);
            std::vector<glm::vec3> filtered(std::size_t(w) * h), unfiltered(filtered.size());
            for (int n = 1; n <= 33; ++n) {
                for (std::size_t p = 0; p < filtered.size(); ++p)
                    for (int c = 0; c < 3; ++c) {
                        filtered[p][c] = level[c] + sigmaF * noise(rng);
                        unfiltered[p][c] =
                            (biased ? shownLevel[c] : level[c]) + sigmaU * noise(rng);
                    }
                const double estimate =
                    addAndEstimate(rows, order, w, h, filtered, withdraw ? unfiltered : filtered);
                if (n == 1) {
                    EXPECT_EQ(estimate, 0.0) << "one frame has no spread";
                    continue;
                }
                if (n != 4 && n != 5 && n != 16 && n != 33) continue;
                double truth = 0;
                for (int c = 0; c < 3; ++c)
                    truth += double(shownSigma) * shownSigma / n /
                             (double(shownLevel[c]) * shownLevel[c] + 0.01);
                truth /= 3;
                EXPECT_NEAR(estimate / truth, 1.0, 0.06)
                    << "withdraw " << withdraw << " biased " << biased << " frames " << n;
            }
        }
}

// A bias of the first frame alone (the paper's clamp in frame 0 of an accumulation) is in one
// half-mean only: with no noise at all, the estimate is the mean's squared bias b^2 / n^2,
// relative, times the ratio of the halves' frame counts (1 when they are equal).
TEST(RowAccumulator, SeesTheFirstFramesBias) {
    const int w = 16, h = 8;
    const CellOrder order(w, 1);
    RowAccumulator rows;
    rows.reset(order, h, false);
    const float truth = 1.0f, bias = -0.3f;
    std::vector<glm::vec3> frame(std::size_t(w) * h);
    for (int n = 1; n <= 12; ++n) {
        std::fill(frame.begin(), frame.end(), glm::vec3(n == 1 ? truth + bias : truth));
        const double estimate = addAndEstimate(rows, order, w, h, frame, frame);
        int nA = 0;
        for (int k = 0; k < n; ++k) nA += RowAccumulator::inFirstHalf(k);
        if (nA == 0 || nA == n) {
            EXPECT_EQ(estimate, 0.0) << "a half without a frame has no spread";
            continue;
        }
        // Frame 0's half holds its bias: (A - B)^2 nA nB / n^2 = b^2 / n^2 x (other / own).
        const double own = RowAccumulator::inFirstHalf(0) ? nA : n - nA, other = n - own;
        const double shown = truth + bias / n;
        const double expected =
            (double(bias) / n) * (bias / n) * (other / own) / (shown * shown + 0.01);
        EXPECT_NEAR(estimate, expected, 1e-6 * expected) << n << " frames";
    }
}

}  // namespace
}  // namespace igi
