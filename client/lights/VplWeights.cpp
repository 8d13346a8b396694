#include "lights/VplWeights.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "math/Color.h"

#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wpsabi"  // the kernels' vectors never cross a call (Lanes.h)
#endif

namespace igi {
namespace {

using lanes::F4;
using lanes::F8;
using lanes::Isa;

/// What the kernels need of the receiving point.
struct Receiver {
    glm::vec3 origin, n, f;
    float dmin2;
    bool ggx;
    const SurfaceBrdf* brdf;
};

// The GGX ranking of the reachable lanes `reach` of the four VPLs from `first`: w times what
// their lobes send toward the point relative to the Lambertian proxy lum(power + glossyPower).
// Scalar and never inlined, so that both kernels run the very same code for it.
__attribute__((noinline)) void rankGroup(const VplChoice& c, std::size_t first, unsigned reach,
                                         unsigned lobes, const Receiver& r, float* k4,
                                         const float* x4, const float* y4, const float* z4) {
    for (unsigned bits = reach; bits; bits &= bits - 1) {
        const int k = __builtin_ctz(bits);
        const glm::vec3 t(x4[k], y4[k], z4[k]);
        const glm::vec3 dir = t / std::sqrt(glm::dot(t, t));  // toward the VPL
        float ratio = 1.0f;
        if (lobes & (1u << k))
            ratio = luminance(c.ggxVpls[c.ggxSlot[first + k]].towards(dir).intensity) /
                    c.lum[first + k];
        if (r.ggx) ratio *= r.brdf->sharpness(dir);
        const float ranked = k4[k] * ratio;
        k4[k] = std::isfinite(ranked) ? std::max(ranked, 1e-6f * k4[k]) : k4[k];
    }
}

// Within each group of four lanes: the lanes moved up by one (two), zeros shifted in, as
// SSE's byte shifts of a 4-lane register do (AVX2's shift each 128-bit half alike).
template <class V>
IGI_LANES V upOne(V a) {
    const V z{};
    if constexpr (lanes::kLanes<V> == 4)
        return __builtin_shufflevector(a, z, 4, 0, 1, 2);
    else
        return __builtin_shufflevector(a, z, 8, 0, 1, 2, 8, 4, 5, 6);
}
template <class V>
IGI_LANES V upTwo(V a) {
    const V z{};
    if constexpr (lanes::kLanes<V> == 4)
        return __builtin_shufflevector(a, z, 4, 5, 0, 1);
    else
        return __builtin_shufflevector(a, z, 8, 9, 0, 1, 8, 9, 4, 5);
}
// Each group of four's inclusive prefix sums, added as Float4's prefixSum adds them:
// [a0, a0+a1, a0+(a1+a2), (a0+a1)+(a2+a3)] (each with the zeros shifted in, as there).
template <class V>
IGI_LANES V groupPrefix(V a) {
    a = a + upOne(a);
    return a + upTwo(a);
}
// Running sums: each group's prefix sums plus the sum before the group, group after group;
// `carry` (the sum before these lanes) becomes that after them.
IGI_LANES F4 carried(F4 prefix, float& carry) {
    const F4 sums = prefix + carry;
    carry = sums[3];
    return sums;
}
IGI_LANES F8 carried(F8 prefix, float& carry) {
    const float c = carry, middle = (prefix + c)[3];  // the first group's sums are prefix + c
    const F8 sums = prefix + F8{c, c, c, c, middle, middle, middle, middle};
    carry = sums[7];
    return sums;
}

// The VPLs i .. i + width - 1 (VplChoice::choose's arithmetic, lane by lane).
template <class V>
IGI_LANES void weigh(const VplChoice& c, std::size_t i, const Receiver& r, float* weight,
                     float* sumW, float* sumR, float& carryW, float& carryR) {
    constexpr int kWidth = lanes::kLanes<V>;
    using lanes::load;
    using lanes::splat;
    const V zero = splat<V>(0.0f), one = splat<V>(1.0f), m2 = splat<V>(r.dmin2);
    const V tx = load<V>(&c.px[i]) - splat<V>(r.origin.x),
            ty = load<V>(&c.py[i]) - splat<V>(r.origin.y),
            tz = load<V>(&c.pz[i]) - splat<V>(r.origin.z);
    const V d2 = tx * tx + ty * ty + tz * tz;
    const V cx = splat<V>(r.n.x) * tx + splat<V>(r.n.y) * ty + splat<V>(r.n.z) * tz;
    const V cf = splat<V>(r.f.x) * tx + splat<V>(r.f.y) * ty + splat<V>(r.f.z) * tz;
    const V cy = zero - (load<V>(&c.nx[i]) * tx + load<V>(&c.ny[i]) * ty + load<V>(&c.nz[i]) * tz);
    // cos_x cos_y = cx cy / d^2 with the unnormalized direction t; max as maxps takes it.
    const V w = load<V>(&c.lum[i]) * cx * cy / (d2 * lanes::select(d2 > m2, d2, m2));
    const auto can = (cx > zero) & (cf > zero) & (cy > zero) & (w > zero);
    V kept = lanes::select(can, w, zero);
    const unsigned reach = lanes::laneBits(can);
    for (int g = 0; g < kWidth / 4; ++g) {
        const unsigned lanesOf = reach >> (4 * g) & 15u, lobes = c.ggxBits[i / 4 + g];
        if (!lanesOf || !(r.ggx || (lanesOf & lobes))) continue;
        float k[kWidth], x[kWidth], y[kWidth], z[kWidth];
        lanes::store(k, kept), lanes::store(x, tx), lanes::store(y, ty), lanes::store(z, tz);
        rankGroup(c, i + 4 * g, lanesOf, lobes, r, k + 4 * g, x + 4 * g, y + 4 * g, z + 4 * g);
        kept = load<V>(k);
    }
    lanes::store(&weight[i], kept);
    lanes::store(&sumW[i], carried(groupPrefix(kept), carryW));
    lanes::store(&sumR[i], carried(groupPrefix(lanes::select(can, one, zero)), carryR));
}

void weighBaseline(const VplChoice& c, const Receiver& r, float* weight, float* sumW, float* sumR) {
    float carryW = 0, carryR = 0;
    for (std::size_t i = 0; i < c.lum.size(); i += 4)
        weigh<F4>(c, i, r, weight, sumW, sumR, carryW, carryR);
}

#if IGI_HAS_AVX2_TARGET
// Eight at a time; the brightness is padded to a multiple of four only, so a last group of
// four goes alone.
IGI_AVX2 void weighAvx2(const VplChoice& c, const Receiver& r, float* weight, float* sumW,
                        float* sumR) {
    float carryW = 0, carryR = 0;
    std::size_t i = 0;
    for (; i + 8 <= c.lum.size(); i += 8) weigh<F8>(c, i, r, weight, sumW, sumR, carryW, carryR);
    for (; i < c.lum.size(); i += 4) weigh<F4>(c, i, r, weight, sumW, sumR, carryW, carryR);
}
#endif

}  // namespace

void vplWeights(const VplChoice& choice, glm::vec3 origin, glm::vec3 n, glm::vec3 f, float dmin2,
                bool ggxReceiver, const SurfaceBrdf* receiver, float* weight, float* sumW,
                float* sumR, Isa isa) {
    const Receiver r{origin, n, f, dmin2, ggxReceiver, receiver};
#if IGI_HAS_AVX2_TARGET
    if (isa == Isa::kAvx2) return weighAvx2(choice, r, weight, sumW, sumR);
#endif
    (void)isa;
    weighBaseline(choice, r, weight, sumW, sumR);
}

}  // namespace igi
