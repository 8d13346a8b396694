#include "VplChoice.h"

#include <algorithm>
#include <cmath>

#include "math/Color.h"
#include "math/Float4.h"

namespace igi {

void VplChoice::prepare(const std::vector<Vpl>& vpls, std::uint32_t points, float u) {
    perPoint = points;
    offset = u;
    const std::size_t padded = (vpls.size() + 3) / 4 * 4;
    for (auto* v : {&px, &py, &pz, &nx, &ny, &nz, &lum}) v->assign(padded, 0.0f);
    glossy.assign(padded / 4, 0);
    anyGlossy = false;
    for (std::size_t i = 0; i < vpls.size(); ++i) {
        const Vpl& v = vpls[i];
        px[i] = v.position.x, py[i] = v.position.y, pz[i] = v.position.z;
        nx[i] = v.normal.x, ny[i] = v.normal.y, nz[i] = v.normal.z;
        lum[i] = std::max(0.0f, luminance(v.power) + luminance(v.glossyPower));
        if (v.glossy()) {
            glossy[i / 4] |= std::uint8_t(1u << (i % 4));
            anyGlossy = true;
        }
    }
}

std::uint32_t VplChoice::choose(glm::vec3 origin, glm::vec3 n, glm::vec3 f, float dmin2,
                                Pick* out) const {
    const std::size_t padded = lum.size();
    thread_local std::vector<float> weight;
    weight.resize(padded);
    const Float4 ox(origin.x), oy(origin.y), oz(origin.z), m2(dmin2), zero(0.0f), one(1.0f);
    Float4 total, count;
    for (std::size_t i = 0; i < padded; i += 4) {
        const Float4 tx = Float4::load(&px[i]) - ox, ty = Float4::load(&py[i]) - oy,
                     tz = Float4::load(&pz[i]) - oz;
        const Float4 d2 = tx * tx + ty * ty + tz * tz;
        const Float4 cx = Float4(n.x) * tx + Float4(n.y) * ty + Float4(n.z) * tz;
        const Float4 cf = Float4(f.x) * tx + Float4(f.y) * ty + Float4(f.z) * tz;
        const Float4 cy = zero - (Float4::load(&nx[i]) * tx + Float4::load(&ny[i]) * ty +
                                  Float4::load(&nz[i]) * tz);
        // cos_x cos_y = cx cy / d^2 with the unnormalized direction t.
        const Float4 w = Float4::load(&lum[i]) * cx * cy / (d2 * max(d2, m2));
        const Float4 can =
            greater(cx, zero) & greater(cf, zero) & greater(cy, zero) & greater(w, zero);
        const Float4 kept = select(can, w, zero);
        kept.store(&weight[i]);
        total = total + kept;
        count = count + select(can, one, zero);
    }
    float t[4], c[4];
    total.store(t), count.store(c);
    const float sum = (t[0] + t[1]) + (t[2] + t[3]);
    const float reachable = (c[0] + c[1]) + (c[2] + c[3]);
    if (!(sum > 0) || !(reachable > 0) || !std::isfinite(sum)) return 0;
    // p_i = (1 - s) w_i / sum + s / reachable for the reachable VPLs, 0 for the others: the
    // CDF walks every VPL, the unreachable ones adding nothing (no sample falls on them).
    const float a = (1.0f - kUniformShare) / sum, b = kUniformShare / reachable;
    const float step = 1.0f / float(perPoint);
    std::uint32_t picked = 0, j = 0;  // j: the next sample, at (j + offset) / perPoint
    float cdf = 0, next = offset * step;
    std::size_t last = padded;  // the last reachable VPL
    for (std::size_t i = 0; i < padded && j < perPoint; ++i) {
        const float w = weight[i];
        if (w > 0) last = i;
        const float p = w > 0 ? a * w + b : 0.0f;
        cdf += p;
        std::uint32_t times = 0;
        while (j < perPoint && next < cdf) ++times, next = (float(++j) + offset) * step;
        if (times > 0) out[picked++] = {std::uint32_t(i), float(times) / (float(perPoint) * p)};
    }
    // The CDF may end a rounding error short of 1: the last reachable VPL takes what is left.
    if (j < perPoint && last < padded) {
        const float p = a * weight[last] + b;
        std::uint32_t times = perPoint - j;
        if (picked > 0 && out[picked - 1].index == last)
            times += std::uint32_t(out[--picked].scale * float(perPoint) * p + 0.5f);
        out[picked++] = {std::uint32_t(last), float(times) / (float(perPoint) * p)};
    }
    return picked;
}

}  // namespace igi
