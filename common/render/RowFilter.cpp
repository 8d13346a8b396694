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
    int count = 0;
    for (int r = 0; r < u.window.count; ++r) {
        const FrameRow& row = *u.window.rows[r];
        for (int qx = x0; qx < x1; ++qx) {
            const int q = u.order.position(qx);
            if (std::fabs(row[R::kDepth][q] - d) > tolerance) continue;  // also rejects +inf
            const glm::vec3 m = at(row, R::kNx, q);
            if (m.x * n.x + m.y * n.y + m.z * n.z < u.s.normalThreshold) continue;
            sum += at(row, R::kEr, q);
            if (u.glossy) glossySum += at(row, R::kGr, q);
            ++count;
        }
    }
    // The pixel itself passes unless it has no normal; then it stands alone.
    const glm::vec3 irradiance = count > 0 ? sum / float(count) : ownE;
    const glm::vec3 glossy = count > 0 ? glossySum / float(count) : ownG;
    put(out, S::kFr, i, reflectance * irradiance + glossy + unfiltered);
}

/// The three lanes of planes `plane` .. `plane` + 2 at position i.
struct Rgb {
    F8 r, g, b;
};
IGI_LANES Rgb load3(const float* const* planes, int i) {
    return {load(planes[0] + i), load(planes[1] + i), load(planes[2] + i)};
}

// Exactly the arithmetic of filterPixel, lane by lane: the tests are negated as there (a NaN
// passes), a rejected neighbour adds +0, which changes no sum (a sum that starts at +0 is
// never -0), and the count is a small integer, exact as a float. `offsets[k]`: from the
// position of a pixel to that of its window's k-th column.
template <bool Glossy, bool Unfiltered>
IGI_LANES void filterLanes(const Setup& u, const int* offsets, int i, ShadedRow& out) {
    const FrameRow& c = *u.window.centre;
    const F8 zero = splat(0.0f), one = splat(1.0f);
    const F8 d = load(c[R::kDepth] + i);
    const F8 nx = load(c[R::kNx] + i), ny = load(c[R::kNy] + i), nz = load(c[R::kNz] + i);
    const F8 tolerance = splat(u.s.depthThreshold) * d, threshold = splat(u.s.normalThreshold);
    F8 sr = zero, sg = zero, sb = zero, gr = zero, gg = zero, gb = zero, count = zero;
    for (int r = 0; r < u.window.count; ++r) {
        const FrameRow& row = *u.window.rows[r];
        const float* depth = row[R::kDepth] + i;
        const float *mx = row[R::kNx] + i, *my = row[R::kNy] + i, *mz = row[R::kNz] + i;
        const float *er = row[R::kEr] + i, *eg = row[R::kEg] + i, *eb = row[R::kEb] + i;
        const float *qr = row[R::kGr] + i, *qg = row[R::kGg] + i, *qb = row[R::kGb] + i;
        for (int k = 0; k < u.s.sizeX; ++k) {
            const int q = offsets[k];
            const F8 dot = load(mx + q) * nx + load(my + q) * ny + load(mz + q) * nz;
            const I8 pass = ~(abs(load(depth + q) - d) > tolerance) & ~(dot < threshold);
            sr += select(pass, load(er + q), zero);
            sg += select(pass, load(eg + q), zero);
            sb += select(pass, load(eb + q), zero);
            if constexpr (Glossy) {
                gr += select(pass, load(qr + q), zero);
                gg += select(pass, load(qg + q), zero);
                gb += select(pass, load(qb + q), zero);
            }
            count += select(pass, one, zero);
        }
    }
    const float* ePlanes[3] = {c[R::kEr], c[R::kEg], c[R::kEb]};
    const float* rPlanes[3] = {c[R::kRr], c[R::kRg], c[R::kRb]};
    const float* uPlanes[3] = {c[R::kUr], c[R::kUg], c[R::kUb]};
    const float* gPlanes[3] = {c[R::kGr], c[R::kGg], c[R::kGb]};
    const Rgb e = load3(ePlanes, i), refl = load3(rPlanes, i), unf = load3(uPlanes, i);
    const Rgb g = Glossy ? load3(gPlanes, i) : Rgb{zero, zero, zero};
    const I8 any = count > zero, finiteDepth = finite(d);
    const F8 fr = select(any, sr / count, e.r), fg = select(any, sg / count, e.g),
             fb = select(any, sb / count, e.b);
    F8 hr = zero, hg = zero, hb = zero;
    if constexpr (Glossy) {
        hr = select(any, gr / count, g.r), hg = select(any, gg / count, g.g);
        hb = select(any, gb / count, g.b);
    }
    store(out[S::kFr] + i, select(finiteDepth, refl.r * fr + hr + unf.r, unf.r));
    store(out[S::kFg] + i, select(finiteDepth, refl.g * fg + hg + unf.g, unf.g));
    store(out[S::kFb] + i, select(finiteDepth, refl.b * fb + hb + unf.b, unf.b));
    if constexpr (Unfiltered) {
        store(out[S::kUr] + i, refl.r * e.r + g.r + unf.r);
        store(out[S::kUg] + i, refl.g * e.g + g.g + unf.g);
        store(out[S::kUb] + i, refl.b * e.b + g.b + unf.b);
    }
}

template <bool Glossy, bool Unfiltered>
IGI_LANES void filterRowWith(const Setup& u, ShadedRow& out) {
    const CellOrder& o = u.order;
    const int n = o.cells(), sizeX = u.s.sizeX, half = (sizeX - 1) / 2;
    // Columns whose window is not shifted: x in [half, width - sizeX + half].
    const int firstUnshifted = half, lastUnshifted = o.width() - sizeX + half;
    constexpr int kMaxLanesWindow = 64;  // wider windows (never set) go one pixel at a time
    int offsets[kMaxLanesWindow];
    for (int kx = 0; kx < n; ++kx) {
        for (int k = 0; k < std::min(sizeX, kMaxLanesWindow); ++k)
            offsets[k] = o.offset(kx, k - half);
        // x = kx + c * n: the lanes c .. c + 7 all unshifted.
        const int cFirst = std::max(0, (firstUnshifted - kx + n - 1) / n);
        const int cLast =
            lastUnshifted >= kx && sizeX <= kMaxLanesWindow ? (lastUnshifted - kx) / n : -1;
        // Shifted windows one pixel at a time; unshifted ones eight at a time, the last eight
        // overlapping the ones before rather than leaving pixels over (a lane's result does not
        // depend on its neighbours', so the pixels written twice get the same bits twice).
        const int columns = o.count(kx);
        const bool lanes = cLast - cFirst + 1 >= kWidth;
        for (int c = 0; c < (lanes ? cFirst : columns); ++c) filterPixel(u, kx + c * n, out);
        if (!lanes) continue;
        for (int c = cFirst;; c += kWidth) {
            const int first = std::min(c, cLast - kWidth + 1);
            filterLanes<Glossy, Unfiltered>(u, offsets, o.start(kx) + first, out);
            if (first + kWidth > cLast) break;
        }
        for (int c = cLast + 1; c < columns; ++c) filterPixel(u, kx + c * n, out);
    }
}

IGI_LANES void filterRowBody(const Setup& u, ShadedRow& out) {
    if (u.glossy) {
        if (u.unfiltered) return filterRowWith<true, true>(u, out);
        return filterRowWith<true, false>(u, out);
    }
    if (u.unfiltered) return filterRowWith<false, true>(u, out);
    filterRowWith<false, false>(u, out);
}

void filterRowBaseline(const Setup& u, ShadedRow& out) {
    filterRowBody(u, out);
}

#if IGI_HAS_AVX2_TARGET
IGI_AVX2 void filterRowAvx2(const Setup& u, ShadedRow& out) {
    filterRowBody(u, out);
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
