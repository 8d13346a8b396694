#include "render/DiscontinuityFilter.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include <glm/geometric.hpp>

#include "math/Float4.h"

namespace igi {

int filterWindowStart(int centre, int size, int extent) {
    const int start = centre - (size - 1) / 2;
    return std::clamp(start, 0, std::max(0, extent - size));
}

namespace {

/// Pixel p of row y, one at a time: the reference the four-wide path below must match bit for
/// bit, used where the window is shifted (the borders) and for the pixels left over.
glm::vec3 filterPixel(const FrameBuffer& f, const DiscontinuityFilterSettings& s, int x, int y0,
                      int y1, std::size_t p) {
    const float d = f.depth[p];
    if (!std::isfinite(d)) return f.unfiltered[p];  // the eye path ended nowhere: no filter
    const int x0 = filterWindowStart(x, s.sizeX, f.width), x1 = std::min(f.width, x0 + s.sizeX);
    const glm::vec3 n = f.normal[p];
    const float tolerance = s.depthThreshold * d;
    glm::vec3 sum(0.0f), glossySum(0.0f);
    int count = 0;
    for (int qy = y0; qy < y1; ++qy) {
        for (int qx = x0; qx < x1; ++qx) {
            const std::size_t q = std::size_t(qy) * f.width + qx;
            if (std::fabs(f.depth[q] - d) > tolerance) continue;  // also rejects +inf
            if (glm::dot(f.normal[q], n) < s.normalThreshold) continue;
            sum += f.irradiance[q];
            glossySum += f.glossy[q];
            ++count;
        }
    }
    // The pixel itself passes unless it has no normal; then it stands alone.
    const glm::vec3 irradiance = count > 0 ? sum / float(count) : f.irradiance[p];
    const glm::vec3 glossy = count > 0 ? glossySum / float(count) : f.glossy[p];
    return f.reflectance[p] * irradiance + glossy + f.unfiltered[p];
}

}  // namespace

// Exactly the arithmetic of filterPixel, lane by lane: the tests are negated as there (a NaN
// passes), a rejected neighbour adds +0, which changes no sum (all terms are >= 0), and the
// count is a small integer, exact as a float.
void DiscontinuityRowFilter::filterFour(int x, int y, int y0, int y1, glm::vec3* out) {
    const FrameBuffer& f = frame_;
    const DiscontinuityFilterSettings& s = settings_;
    const bool glossy = glossy_;
    const PlanarRow& centre = row(y);
    const Float4 d = Float4::load(&centre.depth[x]);
    const Float4 nx = Float4::load(&centre.nx[x]), ny = Float4::load(&centre.ny[x]),
                 nz = Float4::load(&centre.nz[x]);
    const Float4 tolerance = Float4(s.depthThreshold) * d, threshold(s.normalThreshold);
    const Float4 zero(0.0f), one(1.0f);
    Float4 sr, sg, sb, gr, gg, gb, count;
    const int x0 = x - (s.sizeX - 1) / 2;
    for (int qy = y0; qy < y1; ++qy) {
        const PlanarRow& r = row(qy);
        for (int qx = x0; qx < x0 + s.sizeX; ++qx) {
            const Float4 dq = Float4::load(&r.depth[qx]);
            const Float4 dot = Float4::load(&r.nx[qx]) * nx + Float4::load(&r.ny[qx]) * ny +
                               Float4::load(&r.nz[qx]) * nz;
            const Float4 pass = notGreater(abs(dq - d), tolerance) & notLess(dot, threshold);
            sr = sr + select(pass, Float4::load(&r.er[qx]), zero);
            sg = sg + select(pass, Float4::load(&r.eg[qx]), zero);
            sb = sb + select(pass, Float4::load(&r.eb[qx]), zero);
            if (glossy) {
                gr = gr + select(pass, Float4::load(&r.gr[qx]), zero);
                gg = gg + select(pass, Float4::load(&r.gg[qx]), zero);
                gb = gb + select(pass, Float4::load(&r.gb[qx]), zero);
            }
            count = count + select(pass, one, zero);
        }
    }
    const Float4 any = greater(count, zero);
    const Float4 er = select(any, sr / count, Float4::load(&centre.er[x])),
                 eg = select(any, sg / count, Float4::load(&centre.eg[x])),
                 eb = select(any, sb / count, Float4::load(&centre.eb[x]));
    float lanes[6][4];
    er.store(lanes[0]), eg.store(lanes[1]), eb.store(lanes[2]);
    if (glossy) {
        select(any, gr / count, Float4::load(&centre.gr[x])).store(lanes[3]);
        select(any, gg / count, Float4::load(&centre.gg[x])).store(lanes[4]);
        select(any, gb / count, Float4::load(&centre.gb[x])).store(lanes[5]);
    }
    float depth[4];
    d.store(depth);
    const std::size_t p = std::size_t(y) * f.width + x;
    for (int i = 0; i < 4; ++i) {
        const glm::vec3 unfiltered = f.unfiltered[p + i];
        if (!std::isfinite(depth[i])) {
            out[p + i] = unfiltered;
            continue;
        }
        const glm::vec3 e(lanes[0][i], lanes[1][i], lanes[2][i]);
        const glm::vec3 g =
            glossy ? glm::vec3(lanes[3][i], lanes[4][i], lanes[5][i]) : glm::vec3(0.0f);
        out[p + i] = f.reflectance[p + i] * e + g + unfiltered;
    }
}

DiscontinuityRowFilter::DiscontinuityRowFilter(const FrameBuffer& frame,
                                               const DiscontinuityFilterSettings& settings)
    : frame_(frame),
      settings_(settings),
      glossy_(frame.live.has(kGlossy)),  // an empty plane adds zeros: the arithmetic skips it
      rows_(std::size_t(std::max(1, settings.sizeY))) {}

const DiscontinuityRowFilter::PlanarRow& DiscontinuityRowFilter::row(int y) {
    PlanarRow& r = rows_[std::size_t(y) % rows_.size()];
    if (r.y != y) splitRow(y, r);
    return r;
}

void DiscontinuityRowFilter::splitRow(int y, PlanarRow& row) const {
    const FrameBuffer& f = frame_;
    const std::size_t w = std::size_t(f.width), base = std::size_t(y) * w;
    for (auto* v : {&row.depth, &row.nx, &row.ny, &row.nz, &row.er, &row.eg, &row.eb}) v->resize(w);
    std::copy_n(f.depth.begin() + std::ptrdiff_t(base), w, row.depth.begin());
    for (std::size_t x = 0; x < w; ++x) {
        const glm::vec3 n = f.normal[base + x], e = f.irradiance[base + x];
        row.nx[x] = n.x, row.ny[x] = n.y, row.nz[x] = n.z;
        row.er[x] = e.x, row.eg[x] = e.y, row.eb[x] = e.z;
    }
    if (glossy_) {
        for (auto* v : {&row.gr, &row.gg, &row.gb}) v->resize(w);
        for (std::size_t x = 0; x < w; ++x) {
            const glm::vec3 g = f.glossy[base + x];
            row.gr[x] = g.x, row.gg[x] = g.y, row.gb[x] = g.z;
        }
    }
    row.y = y;
}

void DiscontinuityRowFilter::filterRow(int y, std::vector<glm::vec3>& out) {
    const FrameBuffer& f = frame_;
    const DiscontinuityFilterSettings& s = settings_;
    const int y0 = filterWindowStart(y, s.sizeY, f.height), y1 = std::min(f.height, y0 + s.sizeY);
    // Columns whose window is not shifted: [half, width - sizeX + half].
    const int half = (s.sizeX - 1) / 2, lastUnshifted = f.width - s.sizeX + half;
    const std::size_t base = std::size_t(y) * f.width;
    int x = 0;
    for (; x < std::min(half, f.width); ++x) out[base + x] = filterPixel(f, s, x, y0, y1, base + x);
    for (; x + 3 <= lastUnshifted; x += 4) filterFour(x, y, y0, y1, out.data());
    for (; x < f.width; ++x) out[base + x] = filterPixel(f, s, x, y0, y1, base + x);
}

void discontinuityFilterRows(const FrameBuffer& f, const DiscontinuityFilterSettings& s,
                             int rowBegin, int rowEnd, std::vector<glm::vec3>& out) {
    DiscontinuityRowFilter filter(f, s);
    for (int y = rowBegin; y < rowEnd; ++y) filter.filterRow(y, out);
}

void compositeUnfilteredRows(const FrameBuffer& f, int rowBegin, int rowEnd,
                             std::vector<glm::vec3>& out) {
    for (std::size_t p = std::size_t(rowBegin) * f.width; p < std::size_t(rowEnd) * f.width; ++p)
        out[p] = f.reflectance[p] * f.irradiance[p] + f.glossy[p] + f.unfiltered[p];
}

}  // namespace igi
