#pragma once

// Four floats computed lane by lane: SSE where the compiler targets it (every x86-64), plain
// arrays elsewhere. Only what the light tree, the discontinuity buffer and the VPL choice need;
// every operation is IEEE-exact per lane (no approximate reciprocals; prefix sums in one fixed
// order), so both versions give the same bits.
#if defined(__SSE2__)
#include <emmintrin.h>
#else
#include <algorithm>
#include <cmath>
#endif

namespace igi {

#if defined(__SSE2__)
struct Float4 {
    __m128 v;
    Float4() : v(_mm_setzero_ps()) {}
    Float4(float x) : v(_mm_set1_ps(x)) {}  // NOLINT: a scalar broadcasts
    explicit Float4(__m128 x) : v(x) {}
    static Float4 load(const float* p) { return Float4(_mm_loadu_ps(p)); }
    void store(float* p) const { _mm_storeu_ps(p, v); }
};
inline Float4 operator+(Float4 a, Float4 b) {
    return Float4(_mm_add_ps(a.v, b.v));
}
inline Float4 operator-(Float4 a, Float4 b) {
    return Float4(_mm_sub_ps(a.v, b.v));
}
inline Float4 operator*(Float4 a, Float4 b) {
    return Float4(_mm_mul_ps(a.v, b.v));
}
inline Float4 operator/(Float4 a, Float4 b) {
    return Float4(_mm_div_ps(a.v, b.v));
}
inline Float4 min(Float4 a, Float4 b) {
    return Float4(_mm_min_ps(a.v, b.v));
}
inline Float4 max(Float4 a, Float4 b) {
    return Float4(_mm_max_ps(a.v, b.v));
}
inline Float4 sqrt(Float4 a) {
    return Float4(_mm_sqrt_ps(a.v));
}
/// Lane masks: all bits set where the comparison holds.
inline Float4 greater(Float4 a, Float4 b) {
    return Float4(_mm_cmpgt_ps(a.v, b.v));
}
inline Float4 lessEqual(Float4 a, Float4 b) {
    return Float4(_mm_cmple_ps(a.v, b.v));
}
/// !(a > b) and !(a < b): true where either is NaN, as the negated scalar test would be.
inline Float4 notGreater(Float4 a, Float4 b) {
    return Float4(_mm_cmpngt_ps(a.v, b.v));
}
inline Float4 notLess(Float4 a, Float4 b) {
    return Float4(_mm_cmpnlt_ps(a.v, b.v));
}
inline Float4 abs(Float4 a) {
    return Float4(_mm_andnot_ps(_mm_set1_ps(-0.0f), a.v));
}
inline Float4 operator&(Float4 a, Float4 b) {
    return Float4(_mm_and_ps(a.v, b.v));
}
inline Float4 operator|(Float4 a, Float4 b) {
    return Float4(_mm_or_ps(a.v, b.v));
}
/// mask ? a : b, lane by lane.
inline Float4 select(Float4 mask, Float4 a, Float4 b) {
    return Float4(_mm_or_ps(_mm_and_ps(mask.v, a.v), _mm_andnot_ps(mask.v, b.v)));
}
/// Bit i set where lane i of the mask is set.
inline unsigned laneBits(Float4 mask) {
    return unsigned(_mm_movemask_ps(mask.v));
}
/// Inclusive prefix sums of the lanes, added as [a0, a0+a1, a0+(a1+a2), (a0+a1)+(a2+a3)].
inline Float4 prefixSum(Float4 a) {
    a.v = _mm_add_ps(a.v, _mm_castsi128_ps(_mm_slli_si128(_mm_castps_si128(a.v), 4)));
    return Float4(_mm_add_ps(a.v, _mm_castsi128_ps(_mm_slli_si128(_mm_castps_si128(a.v), 8))));
}
/// Lane 3 in every lane.
inline Float4 lastLane(Float4 a) {
    return Float4(_mm_shuffle_ps(a.v, a.v, 0xFF));
}
/// Lane 3 as a float, from the register (a store and a reload would wait for each other).
inline float lastLaneValue(Float4 a) {
    return _mm_cvtss_f32(_mm_shuffle_ps(a.v, a.v, 0xFF));
}
/// [first, a0, a1, a2].
inline Float4 shiftIn(Float4 a, float first) {
    const __m128 shifted = _mm_castsi128_ps(_mm_slli_si128(_mm_castps_si128(a.v), 4));
    return Float4(_mm_move_ss(shifted, _mm_set_ss(first)));
}
/// Rounded up, for lanes in [0, 2^31).
inline Float4 ceilNonNegative(Float4 a) {
    const __m128 down = _mm_cvtepi32_ps(_mm_cvttps_epi32(a.v));
    return Float4(_mm_add_ps(down, _mm_and_ps(_mm_cmpgt_ps(a.v, down), _mm_set1_ps(1.0f))));
}
#else
struct Float4 {
    float v[4];
    Float4() : v{0, 0, 0, 0} {}
    Float4(float x) : v{x, x, x, x} {}  // NOLINT: a scalar broadcasts
    static Float4 load(const float* p) {
        Float4 r;
        for (int i = 0; i < 4; ++i) r.v[i] = p[i];
        return r;
    }
    void store(float* p) const {
        for (int i = 0; i < 4; ++i) p[i] = v[i];
    }
    template <class F>
    static Float4 map(F f) {
        Float4 r;
        for (int i = 0; i < 4; ++i) r.v[i] = f(i);
        return r;
    }
};
inline Float4 operator+(Float4 a, Float4 b) {
    return Float4::map([&](int i) { return a.v[i] + b.v[i]; });
}
inline Float4 operator-(Float4 a, Float4 b) {
    return Float4::map([&](int i) { return a.v[i] - b.v[i]; });
}
inline Float4 operator*(Float4 a, Float4 b) {
    return Float4::map([&](int i) { return a.v[i] * b.v[i]; });
}
inline Float4 operator/(Float4 a, Float4 b) {
    return Float4::map([&](int i) { return a.v[i] / b.v[i]; });
}
inline Float4 min(Float4 a, Float4 b) {
    return Float4::map([&](int i) { return b.v[i] < a.v[i] ? b.v[i] : a.v[i]; });
}
inline Float4 max(Float4 a, Float4 b) {
    return Float4::map([&](int i) { return b.v[i] > a.v[i] ? b.v[i] : a.v[i]; });
}
inline Float4 sqrt(Float4 a) {
    return Float4::map([&](int i) { return std::sqrt(a.v[i]); });
}
inline Float4 greater(Float4 a, Float4 b) {
    return Float4::map([&](int i) { return a.v[i] > b.v[i] ? 1.0f : 0.0f; });
}
inline Float4 lessEqual(Float4 a, Float4 b) {
    return Float4::map([&](int i) { return a.v[i] <= b.v[i] ? 1.0f : 0.0f; });
}
inline Float4 notGreater(Float4 a, Float4 b) {
    return Float4::map([&](int i) { return !(a.v[i] > b.v[i]) ? 1.0f : 0.0f; });
}
inline Float4 notLess(Float4 a, Float4 b) {
    return Float4::map([&](int i) { return !(a.v[i] < b.v[i]) ? 1.0f : 0.0f; });
}
inline Float4 abs(Float4 a) {
    return Float4::map([&](int i) { return std::fabs(a.v[i]); });
}
inline Float4 operator&(Float4 a, Float4 b) {
    return Float4::map([&](int i) { return a.v[i] != 0 && b.v[i] != 0 ? 1.0f : 0.0f; });
}
inline Float4 operator|(Float4 a, Float4 b) {
    return Float4::map([&](int i) { return a.v[i] != 0 || b.v[i] != 0 ? 1.0f : 0.0f; });
}
inline Float4 select(Float4 mask, Float4 a, Float4 b) {
    return Float4::map([&](int i) { return mask.v[i] != 0 ? a.v[i] : b.v[i]; });
}
inline unsigned laneBits(Float4 mask) {
    unsigned bits = 0;
    for (int i = 0; i < 4; ++i) bits |= unsigned(mask.v[i] != 0) << i;
    return bits;
}
inline Float4 prefixSum(Float4 a) {
    const float s1 = a.v[0] + a.v[1];
    Float4 r;
    r.v[0] = a.v[0], r.v[1] = s1, r.v[2] = a.v[0] + (a.v[1] + a.v[2]);
    r.v[3] = s1 + (a.v[2] + a.v[3]);
    return r;
}
inline Float4 lastLane(Float4 a) {
    return Float4(a.v[3]);
}
inline float lastLaneValue(Float4 a) {
    return a.v[3];
}
inline Float4 shiftIn(Float4 a, float first) {
    Float4 r;
    r.v[0] = first, r.v[1] = a.v[0], r.v[2] = a.v[1], r.v[3] = a.v[2];
    return r;
}
inline Float4 ceilNonNegative(Float4 a) {
    return Float4::map([&](int i) { return std::ceil(a.v[i]); });
}
#endif

}  // namespace igi
