#include "render/RowAccumulator.h"

#include <algorithm>
#include <bit>
#include <stdexcept>
#include <type_traits>

#include "image/ImageCompare.h"
#include "render/Accumulator.h"
#include "render/DiscontinuityFilter.h"

#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace igi {
namespace {

using namespace lanes;
using S = ShadedRow;

// A block holds the sums of eight pixels: field f of pixel j at [f * 8 + j]. A kernel of V
// takes a block in kLanes<V> pixels at a time, each as two halves of doubles.
constexpr int kBlock = 8;          // RowAccumulator::kPixelsPerBlock
constexpr int kFilteredSum = 0;    // 3 fields: R, G, B of the filtered frames
constexpr int kUnfilteredSum = 3;  // 3 fields, with withdrawBlur
constexpr int kDifference2 = 6;    // sum of (lum filtered - lum unfiltered)^2, with withdrawBlur
// Then the sums of the even frames (0, 2, 4, ... of the accumulation): 3 fields of the filtered
// frames and, with withdrawBlur, 3 of the unfiltered ones (RowAccumulator::meanRow's error).
constexpr int kEvenWithdraw = 7;
constexpr int kEvenPlain = 3;

/// Accumulator's luminance(glm::vec3) in float, and luminance(glm::dvec3) in double: the same
/// literals (a float literal is not always the double one rounded to float).
template <class V>
IGI_LANES V luminance(V r, V g, V b) {
    if constexpr (std::is_same_v<std::remove_cvref_t<decltype(r[0])>, float>)
        return splat<V>(0.2126f) * r + splat<V>(0.7152f) * g + splat<V>(0.0722f) * b;
    else
        return splat<V>(0.2126) * r + splat<V>(0.7152) * g + splat<V>(0.0722) * b;
}

/// The filtered (f) and unfiltered (u) means R, G, B of the doubles of a block from `at` on:
/// their sums times `inv`.
template <class D>
IGI_LANES void loadMeans(const double* at, D inv, D* f, D* u) {
    for (int c = 0; c < 3; ++c) {
        f[c] = loadDoubles<D>(at + (kFilteredSum + c) * kBlock) * inv;
        u[c] = loadDoubles<D>(at + (kUnfilteredSum + c) * kBlock) * inv;
    }
}

/// Accumulator::ownVariance on the doubles of a block from `at` on, from the sums after the
/// frame.
template <class D>
IGI_LANES D ownVariance(const double* at, D inv, D invDegrees) {
    D f[3], u[3];
    loadMeans(at, inv, f, u);
    const D d = luminance(f[0], f[1], f[2]) - luminance(u[0], u[1], u[2]);
    const D d2 = loadDoubles<D>(at + kDifference2 * kBlock);
    return stdMax(splat<D>(0.0), d2 * inv - d * d) * invDegrees;
}

}  // namespace

struct RowAccumulator::Layout {
    int blocks;
    int fields;
    bool withdraw;
    int even;  ///< the first field of the even frames' sums
    /// Per pixel (varying counts, RowAccumulator::prepareFrame): the frames in its sums and,
    /// of them, those of the first half, each a row of blocks * kBlock doubles in cell order;
    /// null while every pixel has every frame (then the frame counts are the same for all).
    double* counts = nullptr;
    double* firstHalfCounts = nullptr;
    /// blurTolerance(n) for n = 0 .. the largest count (varying counts).
    const double* tolerance = nullptr;
    std::size_t entries() const { return std::size_t(blocks) * kBlock; }
    double* block(std::vector<double>& sums, int y, int b) const {
        return sums.data() + (std::size_t(y) * blocks + b) * fields * kBlock;
    }
    const double* block(const std::vector<double>& sums, int y, int b) const {
        return sums.data() + (std::size_t(y) * blocks + b) * fields * kBlock;
    }
};

namespace {

using namespace lanes;
using Layout = RowAccumulator::Layout;

/// Adds the lanes of `v` to the doubles at `sums` (its two halves).
template <class V>
IGI_LANES void addTo(double* sums, V v) {
    using D = Half<V>;
    constexpr int kHalf = kLanes<V> / 2;
    store(sums, loadDoubles<D>(sums) + lowHalf(v));
    store(sums + kHalf, loadDoubles<D>(sums + kHalf) + highHalf(v));
}

/// The variance addRow writes where each pixel has its own count: ownVariance after `after`
/// frames (0 while there is one), lane by lane.
template <class D>
IGI_LANES D varyingVariance(const double* at, D after) {
    const D one = splat<D>(1.0), zero = splat<D>(0.0);
    const auto some = after > zero, several = after > one;
    const D inv = select(some, one / select(some, after, one), zero);
    const D invDegrees = select(several, one / select(several, after - one, one), zero);
    return select(several, ownVariance(at, inv, invDegrees), zero);
}

/// Accumulator::addRows for one row; `framesBefore` frames are in. Varying: each pixel has its
/// own count (l.counts), and `rendered` (cell order, null: all) says which pixels this frame
/// has: the others' sums and counts are left exactly as they are.
template <class V, bool Varying>
IGI_LANES void addRowBody(const Layout& l, std::vector<double>& sums, int y, const ShadedRow& row,
                          int framesBefore, const float* rendered, double* variance) {
    using D = Half<V>;
    constexpr int kWidth = kLanes<V>, kHalf = kWidth / 2;
    // The variance after this frame, of framesBefore + 1 frames (0 while there is one).
    const D inv = splat<D>(1.0 / (framesBefore + 1.0));
    const D invDegrees = splat<D>(framesBefore > 0 ? 1.0 / framesBefore : 0.0);
    const std::size_t blockBytes = std::size_t(l.fields) * kBlock * sizeof(double);
    const bool even = RowAccumulator::inFirstHalf(framesBefore);
    double* counts = Varying ? l.counts + std::size_t(y) * l.entries() : nullptr;
    double* firstHalfCounts = Varying ? l.firstHalfCounts + std::size_t(y) * l.entries() : nullptr;
    for (int b = 0; b < l.blocks; ++b) {
        double* block = l.block(sums, y, b);
        // The sums stream from memory: ask for the blocks a few ahead.
        const char* ahead = reinterpret_cast<const char*>(block) + 4 * blockBytes;
        for (std::size_t line = 0; line < blockBytes; line += 64)
            __builtin_prefetch(ahead + line, 1);
        for (int j = 0; j < kBlock; j += kWidth) {
            const int i = b * kBlock + j;
            double* s = block + j;
            V f[3] = {load<V>(row[S::kFr] + i), load<V>(row[S::kFg] + i), load<V>(row[S::kFb] + i)};
            // Varying: a pixel not rendered adds exact zeros (selected, so that whatever the
            // frame holds there, even a NaN, never reaches its sums) and no count.
            [[maybe_unused]] Ints<V> hasMask{};
            if constexpr (Varying) {
                const V has = rendered ? load<V>(rendered + i) : splat<V>(1.0f);
                hasMask = has != splat<V>(0.0f);
                for (int c = 0; c < 3; ++c) f[c] = select(hasMask, f[c], splat<V>(0.0f));
                const D h[2] = {lowHalf(has), highHalf(has)};
                for (int k = 0; k < 2; ++k) {
                    double* n = counts + i + k * kHalf;
                    store(n, loadDoubles<D>(n) + h[k]);
                    if (!even) continue;
                    double* nA = firstHalfCounts + i + k * kHalf;
                    store(nA, loadDoubles<D>(nA) + h[k]);
                }
            }
            for (int c = 0; c < 3; ++c) addTo(s + (kFilteredSum + c) * kBlock, f[c]);
            if (even)
                for (int c = 0; c < 3; ++c) addTo(s + (l.even + c) * kBlock, f[c]);
            if (!l.withdraw) continue;
            V u[3] = {load<V>(row[S::kUr] + i), load<V>(row[S::kUg] + i), load<V>(row[S::kUb] + i)};
            if constexpr (Varying)
                for (int c = 0; c < 3; ++c) u[c] = select(hasMask, u[c], splat<V>(0.0f));
            for (int c = 0; c < 3; ++c) addTo(s + (kUnfilteredSum + c) * kBlock, u[c]);
            if (even)
                for (int c = 0; c < 3; ++c) addTo(s + (l.even + 3 + c) * kBlock, u[c]);
            const V lf = luminance(f[0], f[1], f[2]), lu = luminance(u[0], u[1], u[2]);
            const D d[2] = {lowHalf(lf) - lowHalf(lu), highHalf(lf) - highHalf(lu)};
            double* d2 = s + kDifference2 * kBlock;
            for (int h = 0; h < 2; ++h) {
                store(d2 + h * kHalf, loadDoubles<D>(d2 + h * kHalf) + d[h] * d[h]);
                if constexpr (Varying)
                    store(variance + i + h * kHalf,
                          varyingVariance(s + h * kHalf, loadDoubles<D>(counts + i + h * kHalf)));
                else
                    store(variance + i + h * kHalf,
                          framesBefore > 0 ? ownVariance(s + h * kHalf, inv, invDegrees)
                                           : splat<D>(0.0));
            }
        }
    }
}

template <class V, bool Varying>
IGI_LANES void varianceRowBody(const Layout& l, const std::vector<double>& sums, int y, int frames,
                               double* variance) {
    using D = Half<V>;
    constexpr int kHalf = kLanes<V> / 2;
    const D inv = splat<D>(1.0 / double(frames));
    const D invDegrees = splat<D>(frames > 1 ? 1.0 / double(frames - 1) : 0.0);
    const double* counts = Varying ? l.counts + std::size_t(y) * l.entries() : nullptr;
    for (int b = 0; b < l.blocks; ++b)
        for (int j = 0; j < kBlock; j += kHalf) {
            const double* at = l.block(sums, y, b) + j;
            if constexpr (Varying)
                store(variance + b * kBlock + j,
                      varyingVariance(at, loadDoubles<D>(counts + b * kBlock + j)));
            else
                store(variance + b * kBlock + j,
                      frames > 1 ? ownVariance(at, inv, invDegrees) : splat<D>(0.0));
        }
}

/// Per-thread arrays of meanRow.
struct MeanScratch {
    RowPlanes<3> mean;              // the mean's R, G, B in cell order
    std::vector<double> weight;     // the filtered mean's weight in the blend (withdrawBlur)
    std::vector<double> columns;    // the window's variances summed down its rows
    std::vector<double> pooled;     // the larger of a pixel's variance and its window's mean
    std::vector<double> tolerance;  // each pixel's blurTolerance (varying counts)
};

MeanScratch& meanScratch(const CellOrder& order, std::size_t entries) {
    thread_local MeanScratch scratch;
    scratch.mean.resize(order.width());
    scratch.columns.resize(entries + kBlock);
    scratch.pooled.resize(entries + kBlock);
    scratch.weight.resize(entries + kBlock);
    scratch.tolerance.resize(entries + kBlock);
    return scratch;
}

/// What Accumulator::meanRows pools: per position, max(own, mean of the window's variances).
struct Pool {
    const CellOrder& order;
    int noiseX;
    int windowWidth;
    double perWindowPixel;
};

template <class D>
IGI_LANES void poolVariance(const Pool& p, const double* own, const double* columns,
                            double* pooled) {
    constexpr int kWidth = int(sizeof(D) / sizeof(double));
    const CellOrder& o = p.order;
    const int n = o.cells(), width = o.width(), half = (p.noiseX - 1) / 2;
    const int lastUnshifted = width - p.noiseX + half;
    const D perWindowPixel = splat<D>(p.perWindowPixel);
    constexpr int kMaxLanesWindow = 64;
    int offsets[kMaxLanesWindow];
    for (int kx = 0; kx < n; ++kx) {
        for (int k = 0; k < std::min(p.windowWidth, kMaxLanesWindow); ++k)
            offsets[k] = o.offset(kx, k - half);
        const int cFirst = std::max(0, (half - kx + n - 1) / n);
        const int cLast =
            lastUnshifted >= kx && p.noiseX <= kMaxLanesWindow && p.windowWidth == p.noiseX
                ? (lastUnshifted - kx) / n
                : -1;
        for (int c = 0; c < o.count(kx);) {
            const int i = o.start(kx) + c;
            if (c >= cFirst && c + kWidth - 1 <= cLast) {
                D window = splat<D>(0.0);
                for (int k = 0; k < p.windowWidth; ++k)
                    window += loadDoubles<D>(columns + i + offsets[k]);
                store(pooled + i, stdMax(loadDoubles<D>(own + i), window * perWindowPixel));
                c += kWidth;
                continue;
            }
            // The discontinuity buffer's window: every interleaving cell, also at the borders
            // (shifted inward, never cut).
            const int x = kx + c * n;
            const int x0 = std::clamp(x - half, 0, std::max(0, width - p.noiseX));
            double window = 0.0;
            for (int qx = x0; qx < x0 + p.windowWidth; ++qx) window += columns[o.position(qx)];
            pooled[i] = std::max(own[i], window * p.perWindowPixel);
            ++c;
        }
    }
}

/// The estimated relMSE of each pixel of row y's mean after `frames` frames, in cell order,
/// from the sums; `weight`: the filtered mean's weight in the blend (null: 1).
/// RowAccumulator::meanRow says why: the noise, from the halves' difference, and with the
/// unfiltered sums (withdrawBlur) the filter's blur, whose square is estimated without the
/// noise it carries. 0 where a half has no frame; with varying counts (l.counts) each pixel's
/// own `frames` and `firstHalf`.
void estimateErrors(const Layout& l, const std::vector<double>& sums, int y, int frames,
                    int firstHalf, int width, const double* weight, double* error) {
    const double* counts = l.counts ? l.counts + std::size_t(y) * l.entries() : nullptr;
    const double* firstHalfCounts =
        l.counts ? l.firstHalfCounts + std::size_t(y) * l.entries() : nullptr;
    for (int i = 0; i < width; ++i) {
        // nA frames went to the first half's sums (RowAccumulator::inFirstHalf), nB to the
        // other.
        const double n = counts ? counts[i] : double(frames);
        const double nA = counts ? firstHalfCounts[i] : double(firstHalf), nB = n - nA;
        if (nA < 1.0 || nB < 1.0) {  // a half without a frame: no spread to see
            error[i] = 0.0;
            continue;
        }
        // Var(mean) = E[(A - B)^2] nA nB / n^2 (see meanRow); the 1/3 averages the channels.
        const double spread = nA * nB / (n * n), scale = spread / 3.0;
        const double* s = l.block(sums, y, i / kBlock) + i % kBlock;
        const double w = weight ? weight[i] : 1.0;
        double e = 0.0, blurs = 0.0;
        for (int c = 0; c < 3; ++c) {
            const double all = s[(kFilteredSum + c) * kBlock], even = s[(l.even + c) * kBlock];
            double a = even / nA, b = (all - even) / nB;
            double blur = 0.0;  // the squared bias of the filtered mean's share, w^2 bias^2
            if (l.withdraw && w < 1.0) {
                const double uAll = s[(kUnfilteredSum + c) * kBlock];
                const double uEven = s[(l.even + 3 + c) * kBlock];
                const double uA = uEven / nA, uB = (uAll - uEven) / nB;
                // The blur: filtered minus unfiltered mean, d, whose square holds bias^2 and
                // d's own variance, which the halves' d estimate as they do the mean's.
                const double d = (all - uAll) / n, dA = a - uA, dB = b - uB;
                blur = w * w * std::max(0.0, d * d - (dA - dB) * (dA - dB) * spread);
                // The blend's two halves, with the weight of the whole: the mean shown is
                // (nA A + nB B) / n exactly.
                a = w * a + (1.0 - w) * uA;
                b = w * b + (1.0 - w) * uB;
            }
            // truth^2 + 0.01: A B's expectation is truth^2, mean^2's is truth^2 + Var(mean)
            // (meanRow).
            const double denominator = std::max(0.0, a * b) + kRelativeMseEpsilon;
            e += (a - b) * (a - b) / denominator;
            blurs += blur / denominator;
        }
        error[i] = e * scale + blurs / 3.0;
    }
}

struct Mean {
    const Layout& l;
    const CellOrder& order;
    int height;
    int noiseX;
    int noiseY;
    int firstHalf;  ///< frames in the first half's sums, of the `frames` meanRow is asked for
};

/// Writes row y's estimated error (estimateErrors) in image order to `error` (if any): 0
/// while a half has no frame (RowAccumulator::kFirstEstimateFrames), which gives no spread.
void writeErrors(const Mean& m, const std::vector<double>& sums, int y, int frames,
                 const double* weight, float* error) {
    if (!error) return;
    const int width = m.order.width();
    if (!m.l.counts && (m.firstHalf < 1 || m.firstHalf >= frames)) {  // a half without a frame
        std::fill_n(error, width, 0.0f);
        return;
    }
    thread_local std::vector<double> cells;
    cells.resize(std::size_t(width));
    estimateErrors(m.l, sums, y, frames, m.firstHalf, width, weight, cells.data());
    for (int x = 0; x < width; ++x) error[x] = float(cells[std::size_t(m.order.position(x))]);
}

/// 1 / n lane by lane, 0 where n is 0 (a pixel with no frame yet).
template <class D>
IGI_LANES D inverseCounts(D n) {
    const D one = splat<D>(1.0), zero = splat<D>(0.0);
    const auto some = n > zero;
    return select(some, one / select(some, n, one), zero);
}

template <class V, bool Varying>
IGI_LANES void meanRowBody(const Mean& m, const std::vector<double>& sums, int y, int frames,
                           const double* const* variance, glm::vec3* out, float* error) {
    using D = Half<V>;
    constexpr int kWidth = kLanes<V>, kHalf = kWidth / 2;
    const Layout& l = m.l;
    MeanScratch& scratch = meanScratch(m.order, std::size_t(l.blocks) * kBlock);
    float* mean[3] = {scratch.mean[0], scratch.mean[1], scratch.mean[2]};
    const D inv = splat<D>(frames > 0 ? 1.0 / double(frames) : 0.0);
    const double* counts = Varying ? l.counts + std::size_t(y) * l.entries() : nullptr;
    // Each lane's 1 / (its frames): the image's in common, or the pixel's own.
    const auto invAt = [&](int i) {
        if constexpr (Varying)
            return inverseCounts(loadDoubles<D>(counts + i));
        else
            return inv;
    };
    if (!l.withdraw || (!Varying && frames < 2)) {
        for (int b = 0; b < l.blocks; ++b)
            for (int j = 0; j < kBlock; j += kWidth) {
                const double* s = l.block(sums, y, b) + j;
                const int i = b * kBlock + j;
                for (int c = 0; c < 3; ++c) {
                    const double* field = s + (kFilteredSum + c) * kBlock;
                    store(mean[c] + i, narrow(loadDoubles<D>(field) * invAt(i),
                                              loadDoubles<D>(field + kHalf) * invAt(i + kHalf)));
                }
            }
        writeErrors(m, sums, y, frames, nullptr, error);
        return toImageOrderStreamed(m.order, mean[0], mean[1], mean[2], out);
    }
    const D tolerance = splat<D>(Varying ? 0.0 : Accumulator::blurTolerance(frames));
    if constexpr (Varying)
        for (std::size_t i = 0; i < l.entries(); ++i)
            scratch.tolerance[i] = l.tolerance[std::size_t(counts[i])];
    const int y0 = filterWindowStart(y, m.noiseY, m.height);
    const int y1 = std::min(m.height, y0 + m.noiseY);
    const double* own = variance[y - y0];
    const double* pooled = own;
    if (m.noiseX * m.noiseY > 1) {
        // The window's variances summed down its rows, then across its columns: the order of
        // Accumulator::meanRows.
        double* columns = scratch.columns.data();
        const std::size_t entries = std::size_t(l.blocks) * kBlock;
        std::copy_n(variance[0], entries, columns);
        for (int k = 1; k < y1 - y0; ++k)
            for (std::size_t i = 0; i < entries; i += kHalf)
                store(columns + i, loadDoubles<D>(columns + i) + loadDoubles<D>(variance[k] + i));
        const int windowWidth = std::min(m.order.width(), m.noiseX);
        const Pool pool{m.order, m.noiseX, windowWidth, 1.0 / double(windowWidth * (y1 - y0))};
        poolVariance<D>(pool, own, columns, scratch.pooled.data());
        pooled = scratch.pooled.data();
    }
    for (int b = 0; b < l.blocks; ++b) {
        for (int j = 0; j < kBlock; j += kWidth) {
            const double* s = l.block(sums, y, b) + j;
            D halves[3][2];
            for (int h = 0; h < 2; ++h) {
                const int i = b * kBlock + j + h * kHalf;
                const double* at = s + h * kHalf;
                D f[3], u[3];
                loadMeans(at, invAt(i), f, u);
                const D d = luminance(f[0], f[1], f[2]) - luminance(u[0], u[1], u[2]);
                const D laneTolerance =
                    Varying ? loadDoubles<D>(scratch.tolerance.data() + i) : tolerance;
                const D allowed = laneTolerance * loadDoubles<D>(pooled + i);
                const D d2 = d * d;
                // Where every lane keeps the filtered mean (most of a converged image), no
                // division: its quotients would all be dropped.
                auto keep = d2 <= allowed;
                // A pixel of one frame has no spread: it shows its filtered frame, as the
                // whole image does after one frame.
                if constexpr (Varying) keep |= loadDoubles<D>(counts + i) < splat<D>(2.0);
                const D w =
                    allTrue(keep) ? splat<D>(1.0) : select(keep, splat<D>(1.0), allowed / d2);
                for (int c = 0; c < 3; ++c) {
                    halves[c][h] = w * f[c] + (splat<D>(1.0) - w) * u[c];
                    if constexpr (Varying) halves[c][h] = select(keep, f[c], halves[c][h]);
                }
                if (error) store(scratch.weight.data() + i, w);
            }
            for (int c = 0; c < 3; ++c)
                store(mean[c] + b * kBlock + j, narrow(halves[c][0], halves[c][1]));
        }
    }
    writeErrors(m, sums, y, frames, scratch.weight.data(), error);
    toImageOrderStreamed(m.order, mean[0], mean[1], mean[2], out);
}

void addRowBaseline(const Layout& l, std::vector<double>& sums, int y, const ShadedRow& row,
                    int framesBefore, const float* rendered, double* variance) {
    if (l.counts) return addRowBody<F4, true>(l, sums, y, row, framesBefore, rendered, variance);
    addRowBody<F4, false>(l, sums, y, row, framesBefore, rendered, variance);
}
void varianceRowBaseline(const Layout& l, const std::vector<double>& sums, int y, int frames,
                         double* variance) {
    if (l.counts) return varianceRowBody<F4, true>(l, sums, y, frames, variance);
    varianceRowBody<F4, false>(l, sums, y, frames, variance);
}
void meanRowBaseline(const Mean& m, const std::vector<double>& sums, int y, int frames,
                     const double* const* variance, glm::vec3* out, float* error) {
    if (m.l.counts) return meanRowBody<F4, true>(m, sums, y, frames, variance, out, error);
    meanRowBody<F4, false>(m, sums, y, frames, variance, out, error);
}

#if IGI_HAS_AVX2_TARGET
IGI_AVX2 void addRowAvx2(const Layout& l, std::vector<double>& sums, int y, const ShadedRow& row,
                         int framesBefore, const float* rendered, double* variance) {
    if (l.counts) return addRowBody<F8, true>(l, sums, y, row, framesBefore, rendered, variance);
    addRowBody<F8, false>(l, sums, y, row, framesBefore, rendered, variance);
}
IGI_AVX2 void varianceRowAvx2(const Layout& l, const std::vector<double>& sums, int y, int frames,
                              double* variance) {
    if (l.counts) return varianceRowBody<F8, true>(l, sums, y, frames, variance);
    varianceRowBody<F8, false>(l, sums, y, frames, variance);
}
IGI_AVX2 void meanRowAvx2(const Mean& m, const std::vector<double>& sums, int y, int frames,
                          const double* const* variance, glm::vec3* out, float* error) {
    if (m.l.counts) return meanRowBody<F8, true>(m, sums, y, frames, variance, out, error);
    meanRowBody<F8, false>(m, sums, y, frames, variance, out, error);
}
#endif

}  // namespace

void RowAccumulator::reset(const CellOrder& order, int height, bool withdrawBlur, int noiseX,
                           int noiseY) {
    order_ = order;
    height_ = height;
    frames_ = 0;
    firstHalf_ = 0;
    withdrawBlur_ = withdrawBlur;
    noiseX_ = std::max(1, noiseX);
    noiseY_ = std::max(1, noiseY);
    blocks_ = (order.width() + kBlock - 1) / kBlock;
    fields_ = withdrawBlur ? kEvenWithdraw + 6 : kEvenPlain + 3;
    sums_.assign(std::size_t(height) * blocks_ * fields_ * kBlock, 0.0);
    counts_.clear();
    firstHalfCounts_.clear();
    tolerance_.clear();
}

void RowAccumulator::prepareFrame(bool partial) {
    if (partial && counts_.empty()) {
        // From now on each pixel counts its own frames: so far every pixel has every frame.
        const std::size_t entries = std::size_t(height_) * varianceEntries();
        counts_.assign(entries, double(frames_));
        firstHalfCounts_.assign(entries, double(firstHalf_));
    }
    // A pixel has at most the frames so far and this one.
    while (!counts_.empty() && tolerance_.size() < std::size_t(frames_) + 2)
        tolerance_.push_back(Accumulator::blurTolerance(int(tolerance_.size())));
}

RowAccumulator::Layout RowAccumulator::layout() const {
    Layout l{blocks_, fields_, withdrawBlur_, withdrawBlur_ ? kEvenWithdraw : kEvenPlain};
    if (!counts_.empty()) {
        // The kernels write a row's counts only in addRow, each row by one thread.
        l.counts = const_cast<double*>(counts_.data());
        l.firstHalfCounts = const_cast<double*>(firstHalfCounts_.data());
        l.tolerance = tolerance_.data();
    }
    return l;
}

void RowAccumulator::addRow(int y, const ShadedRow& row, double* variance, const float* rendered,
                            Isa isa) {
    if (rendered && counts_.empty())
        throw std::logic_error("RowAccumulator: a partial frame without prepareFrame(true)");
    const Layout l = layout();
#if IGI_HAS_AVX2_TARGET
    if (isa == Isa::kAvx2) return addRowAvx2(l, sums_, y, row, frames_, rendered, variance);
#endif
    addRowBaseline(l, sums_, y, row, frames_, rendered, variance);
}

void RowAccumulator::varianceRow(int y, int frames, double* variance, Isa isa) const {
    const Layout l = layout();
#if IGI_HAS_AVX2_TARGET
    if (isa == Isa::kAvx2) return varianceRowAvx2(l, sums_, y, frames, variance);
#endif
    varianceRowBaseline(l, sums_, y, frames, variance);
}

void RowAccumulator::meanRow(int y, int frames, const double* const* variance, glm::vec3* out,
                             float* error, Isa isa) const {
    const Layout l = layout();
    // Before endFrame, `frames` = frames() + 1 counts the frame being added.
    const int firstHalf = firstHalf_ + (frames > frames_ && inFirstHalf(frames_) ? 1 : 0);
    const Mean m{l, order_, height_, noiseX_, noiseY_, firstHalf};
#if IGI_HAS_AVX2_TARGET
    if (isa == Isa::kAvx2) return meanRowAvx2(m, sums_, y, frames, variance, out, error);
#endif
    meanRowBaseline(m, sums_, y, frames, variance, out, error);
}

double RowAccumulator::frameCount(int x, int y) const {
    if (counts_.empty()) return frames_;
    return counts_[std::size_t(y) * varianceEntries() + std::size_t(order_.position(x))];
}

bool RowAccumulator::inFirstHalf(int frame) {
    // Blocks [2^j, 2^(j+1)) with j odd: 2-3, 8-15, 32-63, ... (the header says why).
    return frame >= 2 && (std::bit_width(unsigned(frame)) - 1) % 2 == 1;
}

std::pair<int, int> RowAccumulator::meanWindow(int y) const {
    if (!withdrawBlur_ || noiseY_ == 1) return {y, y + 1};
    const int y0 = filterWindowStart(y, noiseY_, height_);
    return {y0, std::min(height_, y0 + noiseY_)};
}

}  // namespace igi
