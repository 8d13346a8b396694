#include "render/RowFilter.h"

#include <algorithm>
#include <cmath>

#include <glm/vec3.hpp>

#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace igi {
namespace {

using namespace lanes;
using R = FrameRow;
using S = ShadedRow;

/// What one call filters with, fixed along the row.
struct Setup {
    const FilterWindow& window;
    const CellOrder& order;
    const DiscontinuityFilterSettings& s;
    bool glossy;
    bool unfiltered;
};

glm::vec3 at(const FrameRow& row, int plane, int i) {
    return {row[plane][i], row[plane + 1][i], row[plane + 2][i]};
}

void put(ShadedRow& out, int plane, int i, glm::vec3 v) {
    out[plane][i] = v.x, out[plane + 1][i] = v.y, out[plane + 2][i] = v.z;
}

/// Pixel x, one at a time: the reference the lanes below must match bit for bit (the pixel
/// filter of the discontinuity buffer as discontinuityFilterRows has always computed it), used
/// where the window is shifted (the borders) and for the pixels left over.
void filterPixel(const Setup& u, int x, ShadedRow& out) {
    const FrameRow& c = *u.window.centre;
    const int i = u.order.position(x);
    const glm::vec3 reflectance = at(c, R::kRr, i), unfiltered = at(c, R::kUr, i);
    const glm::vec3 ownE = at(c, R::kEr, i);
    const glm::vec3 ownG = u.glossy ? at(c, R::kGr, i) : glm::vec3(0.0f);
    if (u.unfiltered) put(out, S::kUr, i, reflectance * ownE + ownG + unfiltered);
    const float d = c[R::kDepth][i];
    if (!std::isfinite(d)) {  // the eye path ended nowhere: no filter
        put(out, S::kFr, i, unfiltered);
        return;
    }
    const int width = u.order.width();
    const int x0 = filterWindowStart(x, u.s.sizeX, width), x1 = std::min(width, x0 + u.s.sizeX);
    const glm::vec3 n = at(c, R::kNx, i);
    const float tolerance = u.s.depthThreshold * d;
    glm::vec3 sum(0.0f), glossySum(0.0f);
    int count = 0, glossyCount = 0;
    for (int r = 0; r < u.window.count; ++r) {
        const FrameRow& row = *u.window.rows[r];
        for (int qx = x0; qx < x1; ++qx) {
            const int q = u.order.position(qx);
            if (std::fabs(row[R::kDepth][q] - d) > tolerance) continue;  // also rejects +inf
            const glm::vec3 m = at(row, R::kNx, q);
            const float dot = m.x * n.x + m.y * n.y + m.z * n.z;
            if (dot < u.s.normalThreshold) continue;
            sum += at(row, R::kEr, q);
            ++count;
            // The glossy radiance only from neighbours of nearly the same normal.
            if (u.glossy && !(dot < u.s.glossyNormalThreshold)) {
                glossySum += at(row, R::kGr, q);
                ++glossyCount;
            }
        }
    }
    // The pixel itself passes unless it has no normal; then it stands alone.
    const glm::vec3 irradiance = count > 0 ? sum / float(count) : ownE;
    const glm::vec3 glossy = glossyCount > 0 ? glossySum / float(glossyCount) : ownG;
    put(out, S::kFr, i, reflectance * irradiance + glossy + unfiltered);
}

// Exactly the arithmetic of filterPixel, lane by lane: the tests are negated as there (a NaN
// passes), a rejected neighbour adds +0, which changes no sum (a sum that starts at +0 is
// never -0), and the count is a small integer, exact as a float. `offsets[k]`: from the
// position of a pixel to that of its window's k-th column.
template <class V, bool Glossy, bool Unfiltered>
IGI_LANES void filterLanes(const Setup& u, const int* offsets, int i, ShadedRow& out) {
    using M = Ints<V>;
    const FrameRow& c = *u.window.centre;
    const V zero = splat<V>(0.0f);
    const V d = load<V>(c[R::kDepth] + i);
    const V nx = load<V>(c[R::kNx] + i), ny = load<V>(c[R::kNy] + i), nz = load<V>(c[R::kNz] + i);
    const V tolerance = splat<V>(u.s.depthThreshold) * d;
    const V threshold = splat<V>(u.s.normalThreshold);
    const V glossyThreshold = splat<V>(u.s.glossyNormalThreshold);
    V sr = zero, sg = zero, sb = zero, gr = zero, gg = zero, gb = zero;
    M passed = splatInt<V>(0);  // neighbours that passed, counted in integers (minus the mask)
    M glossyPassed = splatInt<V>(0);  // of which also the glossy test
    for (int r = 0; r < u.window.count; ++r) {
        const FrameRow& row = *u.window.rows[r];
        const float* depth = row[R::kDepth] + i;
        const float *mx = row[R::kNx] + i, *my = row[R::kNy] + i, *mz = row[R::kNz] + i;
        const float *er = row[R::kEr] + i, *eg = row[R::kEg] + i, *eb = row[R::kEb] + i;
        const float *qr = row[R::kGr] + i, *qg = row[R::kGg] + i, *qb = row[R::kGb] + i;
        for (int k = 0; k < u.s.sizeX; ++k) {
            const int q = offsets[k];
            const V dot = load<V>(mx + q) * nx + load<V>(my + q) * ny + load<V>(mz + q) * nz;
            const M pass = ~(abs(load<V>(depth + q) - d) > tolerance) & ~(dot < threshold);
            sr += select(pass, load<V>(er + q), zero);
            sg += select(pass, load<V>(eg + q), zero);
            sb += select(pass, load<V>(eb + q), zero);
            if constexpr (Glossy) {
                const M glossyPass = pass & ~(dot < glossyThreshold);
                gr += select(glossyPass, load<V>(qr + q), zero);
                gg += select(glossyPass, load<V>(qg + q), zero);
                gb += select(glossyPass, load<V>(qb + q), zero);
                glossyPassed -= glossyPass;
            }
            passed -= pass;
        }
    }
    const V count = __builtin_convertvector(passed, V);  // small integers: exact
    const V er = load<V>(c[R::kEr] + i), eg = load<V>(c[R::kEg] + i), eb = load<V>(c[R::kEb] + i);
    const V rr = load<V>(c[R::kRr] + i), rg = load<V>(c[R::kRg] + i), rb = load<V>(c[R::kRb] + i);
    const V ur = load<V>(c[R::kUr] + i), ug = load<V>(c[R::kUg] + i), ub = load<V>(c[R::kUb] + i);
    V hr = zero, hg = zero, hb = zero, og = zero, oh = zero, ob = zero;  // glossy: filtered, own
    const M any = passed > splatInt<V>(0), finiteDepth = finite(d);
    if constexpr (Glossy) {
        const V glossyCount = __builtin_convertvector(glossyPassed, V);
        const M anyGlossy = glossyPassed > splatInt<V>(0);
        og = load<V>(c[R::kGr] + i), oh = load<V>(c[R::kGg] + i), ob = load<V>(c[R::kGb] + i);
        hr = select(anyGlossy, gr / glossyCount, og), hg = select(anyGlossy, gg / glossyCount, oh);
        hb = select(anyGlossy, gb / glossyCount, ob);
    }
    const V fr = select(any, sr / count, er), fg = select(any, sg / count, eg),
            fb = select(any, sb / count, eb);
    store(out[S::kFr] + i, select(finiteDepth, rr * fr + hr + ur, ur));
    store(out[S::kFg] + i, select(finiteDepth, rg * fg + hg + ug, ug));
    store(out[S::kFb] + i, select(finiteDepth, rb * fb + hb + ub, ub));
    if constexpr (Unfiltered) {
        store(out[S::kUr] + i, rr * er + og + ur);
        store(out[S::kUg] + i, rg * eg + oh + ug);
        store(out[S::kUb] + i, rb * eb + ob + ub);
    }
}

template <class V, bool Glossy, bool Unfiltered>
IGI_LANES void filterRowWith(const Setup& u, ShadedRow& out) {
    constexpr int kWidth = kLanes<V>;
    const CellOrder& o = u.order;
    const int n = o.cells(), sizeX = u.s.sizeX, half = (sizeX - 1) / 2;
    // Columns whose window is not shifted: x in [half, width - sizeX + half].
    const int firstUnshifted = half, lastUnshifted = o.width() - sizeX + half;
    constexpr int kMaxLanesWindow = 64;  // wider windows (never set) go one pixel at a time
    int offsets[kMaxLanesWindow];
    for (int kx = 0; kx < n; ++kx) {
        for (int k = 0; k < std::min(sizeX, kMaxLanesWindow); ++k)
            offsets[k] = o.offset(kx, k - half);
        // x = kx + c * n: the lanes c .. c + kWidth - 1 all unshifted.
        const int cFirst = std::max(0, (firstUnshifted - kx + n - 1) / n);
        const int cLast =
            lastUnshifted >= kx && sizeX <= kMaxLanesWindow ? (lastUnshifted - kx) / n : -1;
        // Shifted windows one pixel at a time; unshifted ones a vector at a time, the last
        // vector overlapping the ones before rather than leaving pixels over (a lane's result
        // does not depend on its neighbours', so the pixels written twice get the same bits).
        const int columns = o.count(kx);
        const bool lanes = cLast - cFirst + 1 >= kWidth;
        for (int c = 0; c < (lanes ? cFirst : columns); ++c) filterPixel(u, kx + c * n, out);
        if (!lanes) continue;
        for (int c = cFirst;; c += kWidth) {
            const int first = std::min(c, cLast - kWidth + 1);
            filterLanes<V, Glossy, Unfiltered>(u, offsets, o.start(kx) + first, out);
            if (first + kWidth > cLast) break;
        }
        for (int c = cLast + 1; c < columns; ++c) filterPixel(u, kx + c * n, out);
    }
}

template <class V>
IGI_LANES void filterRowBody(const Setup& u, ShadedRow& out) {
    if (u.glossy) {
        if (u.unfiltered) return filterRowWith<V, true, true>(u, out);
        return filterRowWith<V, true, false>(u, out);
    }
    if (u.unfiltered) return filterRowWith<V, false, true>(u, out);
    filterRowWith<V, false, false>(u, out);
}

void filterRowBaseline(const Setup& u, ShadedRow& out) {
    filterRowBody<F4>(u, out);
}

#if IGI_HAS_AVX2_TARGET
IGI_AVX2 void filterRowAvx2(const Setup& u, ShadedRow& out) {
    filterRowBody<F8>(u, out);
}
#endif

}  // namespace

void filterRow(const FilterWindow& window, const CellOrder& order,
               const DiscontinuityFilterSettings& settings, bool glossy, bool unfiltered,
               ShadedRow& out, Isa isa) {
    out.resize(order.width());
    const Setup u{window, order, settings, glossy, unfiltered};
#if IGI_HAS_AVX2_TARGET
    if (isa == Isa::kAvx2) return filterRowAvx2(u, out);
#endif
    filterRowBaseline(u, out);
}

}  // namespace igi
