#include "render/RowAccumulator.h"

#include <algorithm>

#include "render/Accumulator.h"
#include "render/DiscontinuityFilter.h"

#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace igi {
namespace {

using namespace lanes;
using S = ShadedRow;

// A block holds the sums of eight pixels: field f of pixel j at [f * 8 + j].
constexpr int kFilteredSum = 0;    // 3 fields: R, G, B of the filtered frames
constexpr int kUnfilteredSum = 3;  // 3 fields, with withdrawBlur
constexpr int kDifference2 = 6;    // sum of (lum filtered - lum unfiltered)^2, with withdrawBlur

/// Accumulator's luminance(glm::vec3), in float.
IGI_LANES F8 luminance(F8 r, F8 g, F8 b) {
    return splat(0.2126f) * r + splat(0.7152f) * g + splat(0.0722f) * b;
}
/// Accumulator's luminance(glm::dvec3).
IGI_LANES D4 luminance(D4 r, D4 g, D4 b) {
    return splat(0.2126) * r + splat(0.7152) * g + splat(0.0722) * b;
}

/// Accumulator::ownVariance on four pixels of a block (half h), from the sums after the frame.
IGI_LANES D4 ownVariance(const double* block, int h, D4 inv, D4 invDegrees) {
    auto sum = [&](int field) { return loadD4(block + field * kWidth + 4 * h); };
    const D4 d = luminance(sum(kFilteredSum) * inv, sum(kFilteredSum + 1) * inv,
                           sum(kFilteredSum + 2) * inv) -
                 luminance(sum(kUnfilteredSum) * inv, sum(kUnfilteredSum + 1) * inv,
                           sum(kUnfilteredSum + 2) * inv);
    return stdMax(splat(0.0), sum(kDifference2) * inv - d * d) * invDegrees;
}

struct Layout {
    int blocks;
    int fields;
    bool withdraw;
    double* block(std::vector<double>& sums, int y, int b) const {
        return sums.data() + (std::size_t(y) * blocks + b) * fields * kWidth;
    }
    const double* block(const std::vector<double>& sums, int y, int b) const {
        return sums.data() + (std::size_t(y) * blocks + b) * fields * kWidth;
    }
};

/// Accumulator::addRows for one row; `framesBefore` frames are in.
template <bool Avx2>
IGI_LANES void addRowBody(const Layout& l, std::vector<double>& sums, int y, const ShadedRow& row,
                          int framesBefore, double* variance) {
    // The variance after this frame, of framesBefore + 1 frames (0 while there is one).
    const D4 inv = splat(1.0 / (framesBefore + 1.0));
    const D4 invDegrees = splat(framesBefore > 0 ? 1.0 / framesBefore : 0.0);
    for (int b = 0; b < l.blocks; ++b) {
        double* s = l.block(sums, y, b);
        const int i = b * kWidth;
        const F8 f[3] = {load(row[S::kFr] + i), load(row[S::kFg] + i), load(row[S::kFb] + i)};
        for (int c = 0; c < 3; ++c) {
            double* field = s + (kFilteredSum + c) * kWidth;
            store(field, loadD4(field) + lowD4<Avx2>(f[c]));
            store(field + 4, loadD4(field + 4) + highD4<Avx2>(f[c]));
        }
        if (!l.withdraw) continue;
        const F8 u[3] = {load(row[S::kUr] + i), load(row[S::kUg] + i), load(row[S::kUb] + i)};
        for (int c = 0; c < 3; ++c) {
            double* field = s + (kUnfilteredSum + c) * kWidth;
            store(field, loadD4(field) + lowD4<Avx2>(u[c]));
            store(field + 4, loadD4(field + 4) + highD4<Avx2>(u[c]));
        }
        const F8 lf = luminance(f[0], f[1], f[2]), lu = luminance(u[0], u[1], u[2]);
        const D4 d[2] = {lowD4<Avx2>(lf) - lowD4<Avx2>(lu), highD4<Avx2>(lf) - highD4<Avx2>(lu)};
        double* d2 = s + kDifference2 * kWidth;
        for (int h = 0; h < 2; ++h) {
            store(d2 + 4 * h, loadD4(d2 + 4 * h) + d[h] * d[h]);
            store(variance + i + 4 * h,
                  framesBefore > 0 ? ownVariance(s, h, inv, invDegrees) : splat(0.0));
        }
    }
}

IGI_LANES void varianceRowBody(const Layout& l, const std::vector<double>& sums, int y, int frames,
                               double* variance) {
    const D4 inv = splat(1.0 / double(frames));
    const D4 invDegrees = splat(frames > 1 ? 1.0 / double(frames - 1) : 0.0);
    for (int b = 0; b < l.blocks; ++b)
        for (int h = 0; h < 2; ++h)
            store(variance + b * kWidth + 4 * h,
                  frames > 1 ? ownVariance(l.block(sums, y, b), h, inv, invDegrees) : splat(0.0));
}

/// Per-thread arrays of meanRow.
struct MeanScratch {
    RowPlanes<3> mean;            // the mean's R, G, B in cell order
    std::vector<double> columns;  // the window's variances summed down its rows
    std::vector<double> pooled;   // the larger of a pixel's variance and its window's mean
};

MeanScratch& meanScratch(const CellOrder& order, std::size_t entries) {
    thread_local MeanScratch scratch;
    scratch.mean.resize(order.width());
    scratch.columns.resize(entries + kWidth);
    scratch.pooled.resize(entries + kWidth);
    return scratch;
}

/// What Accumulator::meanRows pools: per position, max(own, mean of the window's variances).
struct Pool {
    const CellOrder& order;
    int noiseX;
    int windowWidth;
    double perWindowPixel;
};

IGI_LANES void poolVariance(const Pool& p, const double* own, const double* columns,
                            double* pooled) {
    const CellOrder& o = p.order;
    const int n = o.cells(), width = o.width(), half = (p.noiseX - 1) / 2;
    const int lastUnshifted = width - p.noiseX + half;
    const D4 perWindowPixel = splat(p.perWindowPixel);
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
            if (c >= cFirst && c + 3 <= cLast) {
                D4 window = splat(0.0);
                for (int k = 0; k < p.windowWidth; ++k) window += loadD4(columns + i + offsets[k]);
                store(pooled + i, stdMax(loadD4(own + i), window * perWindowPixel));
                c += 4;
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

struct Mean {
    const Layout& l;
    const CellOrder& order;
    int height;
    int noiseX;
    int noiseY;
};

IGI_LANES void meanRowBody(const Mean& m, const std::vector<double>& sums, int y, int frames,
                           const double* const* variance, glm::vec3* out) {
    const Layout& l = m.l;
    MeanScratch& scratch = meanScratch(m.order, std::size_t(l.blocks) * kWidth);
    float* mean[3] = {scratch.mean[0], scratch.mean[1], scratch.mean[2]};
    const double invScalar = frames > 0 ? 1.0 / double(frames) : 0.0;
    const D4 inv = splat(invScalar);
    if (!l.withdraw || frames < 2) {
        for (int b = 0; b < l.blocks; ++b) {
            const double* s = l.block(sums, y, b);
            for (int c = 0; c < 3; ++c) {
                const double* field = s + (kFilteredSum + c) * kWidth;
                store(mean[c] + b * kWidth,
                      join(toF4(loadD4(field) * inv), toF4(loadD4(field + 4) * inv)));
            }
        }
        return toImageOrder(m.order, mean[0], mean[1], mean[2], out);
    }
    const D4 tolerance = splat(Accumulator::blurTolerance(frames));
    const int y0 = filterWindowStart(y, m.noiseY, m.height);
    const int y1 = std::min(m.height, y0 + m.noiseY);
    const double* own = variance[y - y0];
    const double* pooled = own;
    if (m.noiseX * m.noiseY > 1) {
        // The window's variances summed down its rows, then across its columns: the order of
        // Accumulator::meanRows.
        double* columns = scratch.columns.data();
        const std::size_t entries = std::size_t(l.blocks) * kWidth;
        std::copy_n(variance[0], entries, columns);
        for (int k = 1; k < y1 - y0; ++k)
            for (std::size_t i = 0; i < entries; i += 4)
                store(columns + i, loadD4(columns + i) + loadD4(variance[k] + i));
        const int windowWidth = std::min(m.order.width(), m.noiseX);
        const Pool pool{m.order, m.noiseX, windowWidth, 1.0 / double(windowWidth * (y1 - y0))};
        poolVariance(pool, own, columns, scratch.pooled.data());
        pooled = scratch.pooled.data();
    }
    for (int b = 0; b < l.blocks; ++b) {
        const double* s = l.block(sums, y, b);
        F4 halves[3][2];
        for (int h = 0; h < 2; ++h) {
            auto meanOf = [&](int field) { return loadD4(s + field * kWidth + 4 * h) * inv; };
            const D4 f[3] = {meanOf(kFilteredSum), meanOf(kFilteredSum + 1),
                             meanOf(kFilteredSum + 2)};
            const D4 u[3] = {meanOf(kUnfilteredSum), meanOf(kUnfilteredSum + 1),
                             meanOf(kUnfilteredSum + 2)};
            const D4 d = luminance(f[0], f[1], f[2]) - luminance(u[0], u[1], u[2]);
            const D4 allowed = tolerance * loadD4(pooled + b * kWidth + 4 * h);
            const D4 d2 = d * d;
            const D4 w = select(d2 <= allowed, splat(1.0), allowed / d2);
            for (int c = 0; c < 3; ++c) halves[c][h] = toF4(w * f[c] + (splat(1.0) - w) * u[c]);
        }
        for (int c = 0; c < 3; ++c) store(mean[c] + b * kWidth, join(halves[c][0], halves[c][1]));
    }
    toImageOrder(m.order, mean[0], mean[1], mean[2], out);
}

void addRowBaseline(const Layout& l, std::vector<double>& sums, int y, const ShadedRow& row,
                    int framesBefore, double* variance) {
    addRowBody<false>(l, sums, y, row, framesBefore, variance);
}
void varianceRowBaseline(const Layout& l, const std::vector<double>& sums, int y, int frames,
                         double* variance) {
    varianceRowBody(l, sums, y, frames, variance);
}
void meanRowBaseline(const Mean& m, const std::vector<double>& sums, int y, int frames,
                     const double* const* variance, glm::vec3* out) {
    meanRowBody(m, sums, y, frames, variance, out);
}

#if IGI_HAS_AVX2_TARGET
IGI_AVX2 void addRowAvx2(const Layout& l, std::vector<double>& sums, int y, const ShadedRow& row,
                         int framesBefore, double* variance) {
    addRowBody<true>(l, sums, y, row, framesBefore, variance);
}
IGI_AVX2 void varianceRowAvx2(const Layout& l, const std::vector<double>& sums, int y, int frames,
                              double* variance) {
    varianceRowBody(l, sums, y, frames, variance);
}
IGI_AVX2 void meanRowAvx2(const Mean& m, const std::vector<double>& sums, int y, int frames,
                          const double* const* variance, glm::vec3* out) {
    meanRowBody(m, sums, y, frames, variance, out);
}
#endif

}  // namespace

void RowAccumulator::reset(const CellOrder& order, int height, bool withdrawBlur, int noiseX,
                           int noiseY) {
    order_ = order;
    height_ = height;
    frames_ = 0;
    withdrawBlur_ = withdrawBlur;
    noiseX_ = std::max(1, noiseX);
    noiseY_ = std::max(1, noiseY);
    blocks_ = (order.width() + kWidth - 1) / kWidth;
    fields_ = withdrawBlur ? 7 : 3;
    sums_.assign(std::size_t(height) * blocks_ * fields_ * kWidth, 0.0);
}

void RowAccumulator::addRow(int y, const ShadedRow& row, double* variance, Isa isa) {
    const Layout l{blocks_, fields_, withdrawBlur_};
#if IGI_HAS_AVX2_TARGET
    if (isa == Isa::kAvx2) return addRowAvx2(l, sums_, y, row, frames_, variance);
#endif
    addRowBaseline(l, sums_, y, row, frames_, variance);
}

void RowAccumulator::varianceRow(int y, int frames, double* variance, Isa isa) const {
    const Layout l{blocks_, fields_, withdrawBlur_};
#if IGI_HAS_AVX2_TARGET
    if (isa == Isa::kAvx2) return varianceRowAvx2(l, sums_, y, frames, variance);
#endif
    varianceRowBaseline(l, sums_, y, frames, variance);
}

void RowAccumulator::meanRow(int y, int frames, const double* const* variance, glm::vec3* out,
                             Isa isa) const {
    const Layout l{blocks_, fields_, withdrawBlur_};
    const Mean m{l, order_, height_, noiseX_, noiseY_};
#if IGI_HAS_AVX2_TARGET
    if (isa == Isa::kAvx2) return meanRowAvx2(m, sums_, y, frames, variance, out);
#endif
    meanRowBaseline(m, sums_, y, frames, variance, out);
}

std::pair<int, int> RowAccumulator::meanWindow(int y) const {
    if (!withdrawBlur_ || noiseY_ == 1) return {y, y + 1};
    const int y0 = filterWindowStart(y, noiseY_, height_);
    return {y0, std::min(height_, y0 + noiseY_)};
}

}  // namespace igi
