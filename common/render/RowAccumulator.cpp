#include "render/RowAccumulator.h"

#include <algorithm>
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

struct Layout {
    int blocks;
    int fields;
    bool withdraw;
    int even;  ///< the first field of the even frames' sums
    double* block(std::vector<double>& sums, int y, int b) const {
        return sums.data() + (std::size_t(y) * blocks + b) * fields * kBlock;
    }
    const double* block(const std::vector<double>& sums, int y, int b) const {
        return sums.data() + (std::size_t(y) * blocks + b) * fields * kBlock;
    }
};

/// Adds the lanes of `v` to the doubles at `sums` (its two halves).
template <class V>
IGI_LANES void addTo(double* sums, V v) {
    using D = Half<V>;
    constexpr int kHalf = kLanes<V> / 2;
    store(sums, loadDoubles<D>(sums) + lowHalf(v));
    store(sums + kHalf, loadDoubles<D>(sums + kHalf) + highHalf(v));
}

/// Accumulator::addRows for one row; `framesBefore` frames are in.
template <class V>
IGI_LANES void addRowBody(const Layout& l, std::vector<double>& sums, int y, const ShadedRow& row,
                          int framesBefore, double* variance) {
    using D = Half<V>;
    constexpr int kWidth = kLanes<V>, kHalf = kWidth / 2;
    // The variance after this frame, of framesBefore + 1 frames (0 while there is one).
    const D inv = splat<D>(1.0 / (framesBefore + 1.0));
    const D invDegrees = splat<D>(framesBefore > 0 ? 1.0 / framesBefore : 0.0);
    const std::size_t blockBytes = std::size_t(l.fields) * kBlock * sizeof(double);
    const bool even = RowAccumulator::inFirstHalf(framesBefore);
    for (int b = 0; b < l.blocks; ++b) {
        double* block = l.block(sums, y, b);
        // The sums stream from memory: ask for the blocks a few ahead.
        const char* ahead = reinterpret_cast<const char*>(block) + 4 * blockBytes;
        for (std::size_t line = 0; line < blockBytes; line += 64)
            __builtin_prefetch(ahead + line, 1);
        for (int j = 0; j < kBlock; j += kWidth) {
            const int i = b * kBlock + j;
            double* s = block + j;
            const V f[3] = {load<V>(row[S::kFr] + i), load<V>(row[S::kFg] + i),
                            load<V>(row[S::kFb] + i)};
            for (int c = 0; c < 3; ++c) addTo(s + (kFilteredSum + c) * kBlock, f[c]);
            if (even)
                for (int c = 0; c < 3; ++c) addTo(s + (l.even + c) * kBlock, f[c]);
            if (!l.withdraw) continue;
            const V u[3] = {load<V>(row[S::kUr] + i), load<V>(row[S::kUg] + i),
                            load<V>(row[S::kUb] + i)};
            for (int c = 0; c < 3; ++c) addTo(s + (kUnfilteredSum + c) * kBlock, u[c]);
            if (even)
                for (int c = 0; c < 3; ++c) addTo(s + (l.even + 3 + c) * kBlock, u[c]);
            const V lf = luminance(f[0], f[1], f[2]), lu = luminance(u[0], u[1], u[2]);
            const D d[2] = {lowHalf(lf) - lowHalf(lu), highHalf(lf) - highHalf(lu)};
            double* d2 = s + kDifference2 * kBlock;
            for (int h = 0; h < 2; ++h) {
                store(d2 + h * kHalf, loadDoubles<D>(d2 + h * kHalf) + d[h] * d[h]);
                store(variance + i + h * kHalf, framesBefore > 0
                                                    ? ownVariance(s + h * kHalf, inv, invDegrees)
                                                    : splat<D>(0.0));
            }
        }
    }
}

template <class V>
IGI_LANES void varianceRowBody(const Layout& l, const std::vector<double>& sums, int y, int frames,
                               double* variance) {
    using D = Half<V>;
    constexpr int kHalf = kLanes<V> / 2;
    const D inv = splat<D>(1.0 / double(frames));
    const D invDegrees = splat<D>(frames > 1 ? 1.0 / double(frames - 1) : 0.0);
    for (int b = 0; b < l.blocks; ++b)
        for (int j = 0; j < kBlock; j += kHalf)
            store(
                variance + b * kBlock + j,
                frames > 1 ? ownVariance(l.block(sums, y, b) + j, inv, invDegrees) : splat<D>(0.0));
}

/// Per-thread arrays of meanRow.
struct MeanScratch {
    RowPlanes<3> mean;            // the mean's R, G, B in cell order
    std::vector<double> weight;   // the filtered mean's weight in the blend (withdrawBlur)
    std::vector<double> columns;  // the window's variances summed down its rows
    std::vector<double> pooled;   // the larger of a pixel's variance and its window's mean
};

MeanScratch& meanScratch(const CellOrder& order, std::size_t entries) {
    thread_local MeanScratch scratch;
    scratch.mean.resize(order.width());
    scratch.columns.resize(entries + kBlock);
    scratch.pooled.resize(entries + kBlock);
    scratch.weight.resize(entries + kBlock);
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

/// The estimated relMSE of each pixel of row y's mean after `frames` (>= 2) frames, in cell
/// order, from the sums; `weight`: the filtered mean's weight in the blend (null: 1); `mean`:
/// the mean's R, G, B as shown (floats, cell order). RowAccumulator::meanRow says why.
void estimateErrors(const Layout& l, const std::vector<double>& sums, int y, int frames,
                    int firstHalf, int width, const double* weight, float* const* mean,
                    double* error) {
    // nA frames went to the first half's sums (RowAccumulator::inFirstHalf), nB to the other.
    const double n = double(frames), nA = double(firstHalf), nB = n - nA;
    // Var(mean) = E[(A - B)^2] nA nB / n^2 (see meanRow); the 1/3 averages the channels.
    const double scale = nA * nB / (n * n) / 3.0;
    for (int i = 0; i < width; ++i) {
        const double* s = l.block(sums, y, i / kBlock) + i % kBlock;
        const double w = weight ? weight[i] : 1.0;
        double e = 0.0;
        for (int c = 0; c < 3; ++c) {
            const double all = s[(kFilteredSum + c) * kBlock], even = s[(l.even + c) * kBlock];
            double a = even / nA, b = (all - even) / nB;
            if (l.withdraw && w < 1.0) {
                // The blend's two halves, with the weight of the whole: the mean shown is
                // (nA A + nB B) / n exactly.
                const double uAll = s[(kUnfilteredSum + c) * kBlock];
                const double uEven = s[(l.even + 3 + c) * kBlock];
                a = w * a + (1.0 - w) * (uEven / nA);
                b = w * b + (1.0 - w) * ((uAll - uEven) / nB);
            }
            const double shown = mean[c][i];
            e += (a - b) * (a - b) / (shown * shown + kRelativeMseEpsilon);
        }
        error[i] = e * scale;
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
/// before two frames, which give no spread.
void writeErrors(const Mean& m, const std::vector<double>& sums, int y, int frames,
                 const double* weight, float* const* mean, float* error) {
    if (!error) return;
    const int width = m.order.width();
    if (frames < 2 || m.firstHalf < 1 || m.firstHalf >= frames) {  // a half without a frame
        std::fill_n(error, width, 0.0f);
        return;
    }
    thread_local std::vector<double> cells;
    cells.resize(std::size_t(width));
    estimateErrors(m.l, sums, y, frames, m.firstHalf, width, weight, mean, cells.data());
    for (int x = 0; x < width; ++x) error[x] = float(cells[std::size_t(m.order.position(x))]);
}

template <class V>
IGI_LANES void meanRowBody(const Mean& m, const std::vector<double>& sums, int y, int frames,
                           const double* const* variance, glm::vec3* out, float* error) {
    using D = Half<V>;
    constexpr int kWidth = kLanes<V>, kHalf = kWidth / 2;
    const Layout& l = m.l;
    MeanScratch& scratch = meanScratch(m.order, std::size_t(l.blocks) * kBlock);
    float* mean[3] = {scratch.mean[0], scratch.mean[1], scratch.mean[2]};
    const D inv = splat<D>(frames > 0 ? 1.0 / double(frames) : 0.0);
    if (!l.withdraw || frames < 2) {
        for (int b = 0; b < l.blocks; ++b)
            for (int j = 0; j < kBlock; j += kWidth) {
                const double* s = l.block(sums, y, b) + j;
                for (int c = 0; c < 3; ++c) {
                    const double* field = s + (kFilteredSum + c) * kBlock;
                    store(mean[c] + b * kBlock + j,
                          narrow(loadDoubles<D>(field) * inv, loadDoubles<D>(field + kHalf) * inv));
                }
            }
        writeErrors(m, sums, y, frames, nullptr, mean, error);
        return toImageOrderStreamed(m.order, mean[0], mean[1], mean[2], out);
    }
    const D tolerance = splat<D>(Accumulator::blurTolerance(frames));
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
                const double* at = s + h * kHalf;
                D f[3], u[3];
                loadMeans(at, inv, f, u);
                const D d = luminance(f[0], f[1], f[2]) - luminance(u[0], u[1], u[2]);
                const D allowed = tolerance * loadDoubles<D>(pooled + b * kBlock + j + h * kHalf);
                const D d2 = d * d;
                // Where every lane keeps the filtered mean (most of a converged image), no
                // division: its quotients would all be dropped.
                const auto keep = d2 <= allowed;
                const D w =
                    allTrue(keep) ? splat<D>(1.0) : select(keep, splat<D>(1.0), allowed / d2);
                for (int c = 0; c < 3; ++c) halves[c][h] = w * f[c] + (splat<D>(1.0) - w) * u[c];
                if (error) store(scratch.weight.data() + b * kBlock + j + h * kHalf, w);
            }
            for (int c = 0; c < 3; ++c)
                store(mean[c] + b * kBlock + j, narrow(halves[c][0], halves[c][1]));
        }
    }
    writeErrors(m, sums, y, frames, scratch.weight.data(), mean, error);
    toImageOrderStreamed(m.order, mean[0], mean[1], mean[2], out);
}

void addRowBaseline(const Layout& l, std::vector<double>& sums, int y, const ShadedRow& row,
                    int framesBefore, double* variance) {
    addRowBody<F4>(l, sums, y, row, framesBefore, variance);
}
void varianceRowBaseline(const Layout& l, const std::vector<double>& sums, int y, int frames,
                         double* variance) {
    varianceRowBody<F4>(l, sums, y, frames, variance);
}
void meanRowBaseline(const Mean& m, const std::vector<double>& sums, int y, int frames,
                     const double* const* variance, glm::vec3* out, float* error) {
    meanRowBody<F4>(m, sums, y, frames, variance, out, error);
}

#if IGI_HAS_AVX2_TARGET
IGI_AVX2 void addRowAvx2(const Layout& l, std::vector<double>& sums, int y, const ShadedRow& row,
                         int framesBefore, double* variance) {
    addRowBody<F8>(l, sums, y, row, framesBefore, variance);
}
IGI_AVX2 void varianceRowAvx2(const Layout& l, const std::vector<double>& sums, int y, int frames,
                              double* variance) {
    varianceRowBody<F8>(l, sums, y, frames, variance);
}
IGI_AVX2 void meanRowAvx2(const Mean& m, const std::vector<double>& sums, int y, int frames,
                          const double* const* variance, glm::vec3* out, float* error) {
    meanRowBody<F8>(m, sums, y, frames, variance, out, error);
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
}

void RowAccumulator::addRow(int y, const ShadedRow& row, double* variance, Isa isa) {
    const Layout l{blocks_, fields_, withdrawBlur_, withdrawBlur_ ? kEvenWithdraw : kEvenPlain};
#if IGI_HAS_AVX2_TARGET
    if (isa == Isa::kAvx2) return addRowAvx2(l, sums_, y, row, frames_, variance);
#endif
    addRowBaseline(l, sums_, y, row, frames_, variance);
}

void RowAccumulator::varianceRow(int y, int frames, double* variance, Isa isa) const {
    const Layout l{blocks_, fields_, withdrawBlur_, withdrawBlur_ ? kEvenWithdraw : kEvenPlain};
#if IGI_HAS_AVX2_TARGET
    if (isa == Isa::kAvx2) return varianceRowAvx2(l, sums_, y, frames, variance);
#endif
    varianceRowBaseline(l, sums_, y, frames, variance);
}

void RowAccumulator::meanRow(int y, int frames, const double* const* variance, glm::vec3* out,
                             float* error, Isa isa) const {
    const Layout l{blocks_, fields_, withdrawBlur_, withdrawBlur_ ? kEvenWithdraw : kEvenPlain};
    // Before endFrame, `frames` = frames() + 1 counts the frame being added.
    const int firstHalf = firstHalf_ + (frames > frames_ && inFirstHalf(frames_) ? 1 : 0);
    const Mean m{l, order_, height_, noiseX_, noiseY_, firstHalf};
#if IGI_HAS_AVX2_TARGET
    if (isa == Isa::kAvx2) return meanRowAvx2(m, sums_, y, frames, variance, out, error);
#endif
    meanRowBaseline(m, sums_, y, frames, variance, out, error);
}

bool RowAccumulator::inFirstHalf(int frame) {
    // One frame of each pair (2i, 2i + 1) to each half, so that the halves never differ by
    // more than a frame; which one by a bit of splitmix64's finalizer of i, a pattern that
    // neither the frame's parity nor its Sobol' bits follow.
    std::uint64_t z = std::uint64_t(frame >> 1) + 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return ((z ^ (z >> 31)) & 1u) == std::uint64_t(frame & 1);
}

std::pair<int, int> RowAccumulator::meanWindow(int y) const {
    if (!withdrawBlur_ || noiseY_ == 1) return {y, y + 1};
    const int y0 = filterWindowStart(y, noiseY_, height_);
    return {y0, std::min(height_, y0 + noiseY_)};
}

}  // namespace igi
