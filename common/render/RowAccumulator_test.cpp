#include "render/RowAccumulator.h"

#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <utility>
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
                                rows.addRow(y, shaded, variance[std::size_t(y)].data(), nullptr,
                                            isa);
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

/// What the compositor does with one frame, image order in and out: adds it (`rendered`, image
/// order, 1 or 0 per pixel: null for every pixel), ends it, and reads every row's mean and
/// estimated error after it.
struct Readout {
    std::vector<glm::vec3> mean;
    std::vector<float> error;
};
Readout addFrame(RowAccumulator& rows, const CellOrder& order, int w, int h,
                 const std::vector<glm::vec3>& filtered, const std::vector<glm::vec3>& unfiltered,
                 const std::vector<float>* rendered, lanes::Isa isa) {
    std::vector<std::vector<double>> variance(std::size_t(h),
                                              std::vector<double>(rows.varianceEntries()));
    ShadedRow shaded;
    shaded.resize(w);
    std::vector<float> mask(rows.varianceEntries(), 1.0f);
    rows.prepareFrame(rendered != nullptr);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const std::size_t p = std::size_t(y) * w + x;
            for (int c = 0; c < 3; ++c) {
                shaded[ShadedRow::kFr + c][order.position(x)] = filtered[p][c];
                shaded[ShadedRow::kUr + c][order.position(x)] = unfiltered[p][c];
            }
            if (rendered) mask[std::size_t(order.position(x))] = (*rendered)[p];
        }
        rows.addRow(y, shaded, variance[std::size_t(y)].data(), rendered ? mask.data() : nullptr,
                    isa);
    }
    rows.endFrame();
    Readout out{std::vector<glm::vec3>(std::size_t(w) * h), std::vector<float>(std::size_t(w) * h)};
    for (int y = 0; y < h; ++y) {
        const auto [first, last] = rows.meanWindow(y);
        std::vector<const double*> window;
        for (int k = first; k < last; ++k) window.push_back(variance[std::size_t(k)].data());
        rows.meanRow(y, rows.frames(), window.data(), out.mean.data() + std::size_t(y) * w,
                     out.error.data() + std::size_t(y) * w, isa);
    }
    return out;
}

/// Adds one frame of `filtered` and `unfiltered` (image order, w x h) to `rows` and returns
/// the mean over the image of the error meanRow estimates after it.
double addAndEstimate(RowAccumulator& rows, const CellOrder& order, int w, int h,
                      const std::vector<glm::vec3>& filtered,
                      const std::vector<glm::vec3>& unfiltered) {
    const Readout r = addFrame(rows, order, w, h, filtered, unfiltered, nullptr, lanes::bestIsa());
    double sum = 0;
    for (const float e : r.error) sum += e;
    return sum / (double(w) * h);
}

// The image's estimated relMSE (the pixels' mean) and the mean's actual relMSE against
// `truth`, the same at every pixel.
std::pair<double, double> estimateAndActual(const Readout& r, glm::vec3 truth) {
    double estimate = 0, actual = 0;
    for (std::size_t p = 0; p < r.error.size(); ++p) {
        estimate += r.error[p];
        for (int c = 0; c < 3; ++c) {
            const double d = r.mean[p][c] - truth[c];
            actual += d * d / (double(truth[c]) * truth[c] + 0.01) / 3.0;
        }
    }
    return {estimate / double(r.error.size()), actual / double(r.error.size())};
}

// A constant image plus Gaussian noise of a known spread: after n frames the mean's relMSE is
// sigma^2 / n / (c^2 + 0.01) per channel, and the estimate from the two half-means must find
// it within a few per cent (its own noise over 64 x 64 x 3 values is about 1.3 %), at even and
// odd n, where the filtered frames are shown (no bias between the planes: w = 1) and where the
// progressive filter withdraws the blur (a bias between them: the noisier unfiltered mean is
// shown). `actual`: the mean's relMSE against the known level, which the model must give.
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
                const Readout r =
                    addFrame(rows, order, w, h, filtered, withdraw ? unfiltered : filtered, nullptr,
                             lanes::bestIsa());
                const auto [estimate, actual] = estimateAndActual(r, shownLevel);
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
                const std::string what = "withdraw " + std::to_string(withdraw) + " biased " +
                                         std::to_string(biased) + " frames " + std::to_string(n);
                EXPECT_NEAR(actual / truth, 1.0, 0.06) << what;  // the model holds
                if (withdraw && !biased) {
                    // Pixels that the filter withdraws by chance count their chance difference
                    // as blur (RowAccumulator::meanRow): the estimate errs high, up to 1.5x
                    // by 33 frames where the unfiltered frames are 3x as noisy as these.
                    EXPECT_GT(estimate / truth, 0.94) << what;
                    EXPECT_LT(estimate / truth, 1.6) << what;
                } else {
                    EXPECT_NEAR(estimate / truth, 1.0, 0.06) << what;
                }
            }
        }
}

// The halves are aligned blocks of 2^j frames (each stratified as the whole sequence of pixel
// positions is), alternating from block to block, and both have a frame from
// kFirstEstimateFrames on, never before.
TEST(RowAccumulator, HalvesAreAlternateBlocksOfPowersOfTwoFrames) {
    int nA = 0;
    for (int frame = 0; frame < 4096; ++frame) {
        int j = 0;
        while ((2 << j) <= frame) ++j;  // frame in [2^j, 2^(j+1)); frames 0 and 1 with j = 0
        EXPECT_EQ(RowAccumulator::inFirstHalf(frame), frame >= 2 && j % 2 == 1) << frame;
        nA += RowAccumulator::inFirstHalf(frame);
        const int n = frame + 1;
        EXPECT_EQ(nA > 0 && nA < n, n >= RowAccumulator::kFirstEstimateFrames) << n << " frames";
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
        // The denominator: A B, frame 0's half-mean times the other's.
        const double ownMean = truth + bias / own;
        const double expected =
            (double(bias) / n) * (bias / n) * (other / own) / (ownMean * truth + 0.01);
        EXPECT_NEAR(estimate, expected, 1e-6 * expected) << n << " frames";
    }
}

void expectSame(const Readout& got, const Readout& expected, std::size_t p,
                const std::string& what) {
    EXPECT_EQ(std::memcmp(&got.mean[p], &expected.mean[p], sizeof(glm::vec3)), 0)
        << what << " pixel " << p << ": " << got.mean[p].x << " vs " << expected.mean[p].x;
    EXPECT_EQ(got.error[p], expected.error[p]) << what << " pixel " << p;
}

// Counting frames per pixel (adaptive tiles) must not move a bit while every pixel has every
// frame: the same frames with per-pixel counts from the third frame on (all rendered) and
// without them give the same means and estimates, in every window, cell order and instruction
// set.
TEST(RowAccumulator, PerPixelCountsOfFullFramesChangeNothing) {
    const int windows[][2] = {{3, 3}, {1, 1}, {4, 2}};
    for (const auto& window : windows)
        for (const bool withdraw : {true, false})
            for (const int cells : {1, 3})
                for (const lanes::Isa isa : isas()) {
                    const int w = 21, h = 9;
                    const CellOrder order(w, cells);
                    RowAccumulator uniform, counting;
                    uniform.reset(order, h, withdraw, window[0], window[1]);
                    counting.reset(order, h, withdraw, window[0], window[1]);
                    const std::vector<float> all(std::size_t(w) * h, 1.0f);
                    std::mt19937 rng(11);
                    std::vector<glm::vec3> filtered, unfiltered;
                    for (int frame = 0; frame < 6; ++frame) {
                        randomImages(w, h, rng, filtered, unfiltered);
                        const Readout a =
                            addFrame(uniform, order, w, h, filtered, unfiltered, nullptr, isa);
                        const Readout b = addFrame(counting, order, w, h, filtered, unfiltered,
                                                   frame >= 2 ? &all : nullptr, isa);
                        EXPECT_EQ(counting.countsPerPixel(), frame >= 2);
                        for (std::size_t p = 0; p < a.mean.size(); ++p)
                            expectSame(b, a, p, "frame " + std::to_string(frame));
                    }
                }
}

// A pixel a frame does not render keeps its sums: with a window of one pixel (no pooling
// across pixels), the pixels left out from the fourth frame on show, after eight frames, the
// mean and estimate of an accumulation of their first three frames, bit for bit; the others
// those of all eight; and their counts say so.
TEST(RowAccumulator, PixelsLeftOutKeepTheirMeanAndEstimate) {
    for (const bool withdraw : {true, false})
        for (const lanes::Isa isa : isas()) {
            const int w = 19, h = 6;
            const CellOrder order(w, 2);
            RowAccumulator partial, first3, all8;
            for (RowAccumulator* r : {&partial, &first3, &all8}) r->reset(order, h, withdraw);
            std::vector<float> rendered(std::size_t(w) * h, 1.0f);
            for (std::size_t p = 0; p < rendered.size(); ++p)
                if ((p % 7) < 3) rendered[p] = 0.0f;  // left out from the fourth frame on
            std::mt19937 rng(5);
            std::vector<glm::vec3> filtered, unfiltered;
            Readout got, early, full;
            for (int frame = 0; frame < 8; ++frame) {
                randomImages(w, h, rng, filtered, unfiltered);
                if (frame >= 3)  // what a frame holds where it renders nothing must not count
                    for (std::size_t p = 0; p < filtered.size(); ++p)
                        if (rendered[p] == 0.0f) filtered[p] = glm::vec3(frame % 2 ? NAN : 1e30f);
                got = addFrame(partial, order, w, h, filtered, unfiltered,
                               frame >= 3 ? &rendered : nullptr, isa);
                if (frame < 3)
                    early = addFrame(first3, order, w, h, filtered, unfiltered, nullptr, isa);
                full = addFrame(all8, order, w, h, filtered, unfiltered, nullptr, isa);
            }
            for (std::size_t p = 0; p < rendered.size(); ++p) {
                const bool left = rendered[p] == 0.0f;
                expectSame(got, left ? early : full, p,
                           std::string(left ? "left out" : "rendered") + " withdraw " +
                               std::to_string(withdraw));
                EXPECT_EQ(partial.frameCount(int(p % std::size_t(w)), int(p / std::size_t(w))),
                          left ? 3.0 : 8.0);
            }
        }
}

// A pixel left out for a while and then rendered again (a lowered target) averages exactly
// the frames it has: sum / count.
TEST(RowAccumulator, APixelRenderedAgainAveragesItsOwnFrames) {
    const int w = 9, h = 3;
    const CellOrder order(w, 1);
    RowAccumulator rows;
    rows.reset(order, h, false);
    std::vector<float> rendered(std::size_t(w) * h, 1.0f);
    rendered[4] = 0.0f;
    std::mt19937 rng(9);
    std::vector<glm::vec3> filtered, unfiltered;
    double sum = 0.0;
    int count = 0;
    Readout out;
    for (int frame = 0; frame < 10; ++frame) {
        randomImages(w, h, rng, filtered, unfiltered);
        const bool left = frame >= 3 && frame < 6;
        if (!left) {
            sum += double(filtered[4].x);
            ++count;
        }
        out = addFrame(rows, order, w, h, filtered, unfiltered, left ? &rendered : nullptr,
                       lanes::bestIsa());
    }
    EXPECT_EQ(count, 7);
    EXPECT_EQ(rows.frameCount(4, 0), 7.0);
    EXPECT_EQ(out.mean[4].x, float(sum * (1.0 / 7.0)));
    EXPECT_GT(out.error[4], 0.0f);
}

}  // namespace
}  // namespace igi

namespace igi {
namespace {

// The filtered frames blurred (here: brighter by a fraction `blur` everywhere) by about what
// the filter's own test can tell from noise: it withdraws partly (0 < w < 1), and the mean
// shown keeps w times the blur. The estimate holds that bias, w^2 blur^2 (RowAccumulator::
// meanRow), beside the noise; without it, it would give the noise alone, a fraction of the
// error.
TEST(RowAccumulator, SeesTheBlurTheFilterKeepsWhereItWithdraws) {
    const int w = 64, h = 64;
    const glm::vec3 level(0.5f, 1.0f, 2.0f);
    const float blur = 0.16f, sigmaF = 0.05f, sigmaU = 0.15f;
    std::mt19937 rng(7);
    std::normal_distribution<float> noise(0.0f, 1.0f);
    const CellOrder order(w, 3);
    RowAccumulator rows;
    rows.reset(order, h, true, 3, 3);
    std::vector<glm::vec3> filtered(std::size_t(w) * h), unfiltered(filtered.size());
    for (int n = 1; n <= 64; ++n) {
        for (std::size_t p = 0; p < filtered.size(); ++p)
            for (int c = 0; c < 3; ++c) {
                filtered[p][c] = level[c] * (1.0f + blur) + sigmaF * noise(rng);
                unfiltered[p][c] = level[c] + sigmaU * noise(rng);
            }
        const Readout r =
            addFrame(rows, order, w, h, filtered, unfiltered, nullptr, lanes::bestIsa());
        if (n != 16 && n != 64) continue;
        const auto [estimate, actual] = estimateAndActual(r, level);
        EXPECT_GT(estimate / actual, 0.7) << n << " frames";
        EXPECT_LT(estimate / actual, 1.3) << n << " frames";
    }
}

}  // namespace
}  // namespace igi
