#pragma once

// Floats (and 32-bit integers, and doubles) computed lane by lane, written once as GCC and
// Clang vector extensions over a vector type V: F4, four floats, which any x86-64 runs as SSE2,
// or F8, eight floats, which functions marked IGI_AVX2 run as AVX2 where the processor has it
// (hasAvx2). A kernel is a template on V, instantiated twice; the build flags stay those of any
// x86-64 (no -march=native). F8 belongs inside IGI_AVX2 functions only: under GCC its helpers
// use AVX instructions.
//
// Every operation is IEEE-exact per lane, as the scalar code it replaces: the avx2 target
// does not enable FMA (and igi_common and igi_protocol build with -ffp-contract=off besides),
// and nothing here uses approximate reciprocals. A kernel built from these therefore gives the
// same bits in both instantiations and as its scalar reference.
//
// Helpers are always inlined: a vector argument passed by value between functions of
// different targets would change the calling convention (hence the -Wpsabi note, silenced).

#include <cstdint>
#include <cstring>
#include <type_traits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

#define IGI_LANES inline __attribute__((always_inline))
#if defined(__x86_64__)
/// Marks a function whose body (and everything inlined into it) may use AVX2.
#define IGI_AVX2 __attribute__((target("avx2")))
#define IGI_HAS_AVX2_TARGET 1
#else
#define IGI_HAS_AVX2_TARGET 0
#endif

namespace igi::lanes {

typedef float F4 __attribute__((vector_size(16)));
typedef float F8 __attribute__((vector_size(32)));
typedef std::int32_t I4 __attribute__((vector_size(16)));
typedef std::int32_t I8 __attribute__((vector_size(32)));
typedef std::uint32_t U4 __attribute__((vector_size(16)));
typedef std::uint32_t U8 __attribute__((vector_size(32)));
typedef double D2 __attribute__((vector_size(16)));
typedef double D4 __attribute__((vector_size(32)));

/// Whether this processor runs AVX2 code (asked once; IGI_NO_AVX2=1 says no).
bool hasAvx2();

/// The code a kernel runs: four lanes of SSE2 (any x86-64) or eight of AVX2, the same bits.
enum class Isa { kBaseline, kAvx2 };
inline Isa bestIsa() {
    return hasAvx2() ? Isa::kAvx2 : Isa::kBaseline;
}

/// Floats per vector.
template <class V>
constexpr int kLanes = int(sizeof(V) / sizeof(float));
/// The 32-bit integers of V's lanes (also what comparing two V gives: lanes of all ones or
/// all zeros).
template <class V>
using Ints = std::conditional_t<sizeof(V) == 16, I4, I8>;
/// Half of V's lanes as doubles.
template <class V>
using Half = std::conditional_t<sizeof(V) == 16, D2, D4>;

template <class V>
IGI_LANES V load(const float* p) {
    V v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
template <class V>
IGI_LANES V loadDoubles(const double* p) {
    V v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
template <class V>
IGI_LANES void store(float* p, V v) {
    std::memcpy(p, &v, sizeof v);
}
template <class V>
IGI_LANES void store(double* p, V v) {
    std::memcpy(p, &v, sizeof v);
}

template <class V>
IGI_LANES V splat(float x) {
    return V{} + x;
}
template <class V>
IGI_LANES V splat(double x) {
    return V{} + x;
}
template <class V>
IGI_LANES Ints<V> splatInt(std::int32_t x) {
    return Ints<V>{} + x;
}

/// mask ? a : b, lane by lane, for floats or doubles; `mask` is a comparison of the same type.
template <class V, class M>
IGI_LANES V select(M mask, V a, V b) {
    static_assert(sizeof(M) == sizeof(V));
    return (V)((mask & (M)a) | (~mask & (M)b));
}
template <class V>
IGI_LANES V abs(V a) {
    return (V)((Ints<V>)a & splatInt<V>(0x7FFFFFFF));
}
/// All ones where the lane is finite (not NaN, not +-inf).
template <class V>
IGI_LANES Ints<V> finite(V a) {
    return ((Ints<V>)a & splatInt<V>(0x7F800000)) != splatInt<V>(0x7F800000);
}
/// Whether every lane of a comparison of doubles holds (the lanes folded onto the first by
/// shuffles, which both instruction sets do in a few steps).
template <class M>
IGI_LANES bool allTrue(M mask) {
    if constexpr (sizeof(M) == 16) {
        return (mask & __builtin_shufflevector(mask, mask, 1, 0))[0] != 0;
    } else {
        const M half = mask & __builtin_shufflevector(mask, mask, 2, 3, 0, 1);
        return (half & __builtin_shufflevector(half, half, 1, 0, 3, 2))[0] != 0;
    }
}
/// std::max(a, b) lane by lane: (a < b) ? b : a, so a NaN in b gives a, as the scalar does.
template <class V>
IGI_LANES V stdMax(V a, V b) {
    return select(a < b, b, a);
}

#if IGI_HAS_AVX2_TARGET && !defined(__clang__)
// GCC 12 widens four floats to doubles two at a time through the stack; AVX has one
// instruction for it. Not inlined by force (a target mismatch would be an error where the
// kernel is instantiated for the baseline), but inlined where the AVX2 kernels call it.
IGI_AVX2 inline D4 widenAvx(F4 a) {
    return (D4)__builtin_ia32_cvtps2pd256(a);
}
#endif

/// The first and the second half of V's lanes, as doubles (exact).
IGI_LANES D2 lowHalf(F4 a) {
    return __builtin_convertvector(__builtin_shufflevector(a, a, 0, 1), D2);
}
IGI_LANES D2 highHalf(F4 a) {
    return __builtin_convertvector(__builtin_shufflevector(a, a, 2, 3), D2);
}
IGI_LANES D4 lowHalf(F8 a) {
    const F4 low = __builtin_shufflevector(a, a, 0, 1, 2, 3);
#if IGI_HAS_AVX2_TARGET && !defined(__clang__)
    return widenAvx(low);
#else
    return __builtin_convertvector(low, D4);
#endif
}
IGI_LANES D4 highHalf(F8 a) {
    const F4 high = __builtin_shufflevector(a, a, 4, 5, 6, 7);
#if IGI_HAS_AVX2_TARGET && !defined(__clang__)
    return widenAvx(high);
#else
    return __builtin_convertvector(high, D4);
#endif
}
/// Two halves of doubles back to floats (rounded as static_cast<float>), in one vector.
IGI_LANES F4 narrow(D2 low, D2 high) {
    return __builtin_convertvector(__builtin_shufflevector(low, high, 0, 1, 2, 3), F4);
}
IGI_LANES F8 narrow(D4 low, D4 high) {
    typedef float F4h __attribute__((vector_size(16)));
    const F4h a = __builtin_convertvector(low, F4h), b = __builtin_convertvector(high, F4h);
    return __builtin_shufflevector(a, b, 0, 1, 2, 3, 4, 5, 6, 7);
}

/// The square root of each lane, correctly rounded (sqrtps), as std::sqrt gives it.
IGI_LANES F4 squareRoot(F4 a) {
    return __builtin_ia32_sqrtps(a);
}
/// Bit i set where lane i of a comparison holds.
IGI_LANES unsigned laneBits(I4 mask) {
    return unsigned(__builtin_ia32_movmskps((F4)mask));
}
#if IGI_HAS_AVX2_TARGET
// AVX instructions: not inlined by force, as widenAvx, but inlined into the AVX2 kernels.
IGI_AVX2 inline F8 squareRoot(F8 a) {
    return __builtin_ia32_sqrtps256(a);
}
IGI_AVX2 inline unsigned laneBits(I8 mask) {
    return unsigned(__builtin_ia32_movmskps256((F8)mask));
}
#endif

/// The bytes at p, one per lane, zero-extended to 32 bits.
IGI_LANES U4 loadBytes4(const std::uint8_t* p) {
#if defined(__SSE2__)
    std::int32_t word;
    std::memcpy(&word, p, sizeof word);
    const __m128i zero = _mm_setzero_si128();
    const __m128i bytes = _mm_cvtsi32_si128(word);
    return (U4)_mm_unpacklo_epi16(_mm_unpacklo_epi8(bytes, zero), zero);
#else
    return U4{p[0], p[1], p[2], p[3]};
#endif
}

}  // namespace igi::lanes

#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
