#pragma once

// Eight floats (eight 32-bit integers, four doubles) computed lane by lane, written once as
// GCC and Clang vector extensions: the same kernel compiles to pairs of SSE2 instructions for
// any x86-64, and to single AVX2 instructions when it is inlined into a function marked
// IGI_AVX2, which runs only where the processor has AVX2 (hasAvx2). The build flags stay
// those of any x86-64 (no -march=native): the AVX2 code exists beside the baseline code.
//
// Every operation is IEEE-exact per lane, as the scalar code it replaces: the avx2 target
// does not enable FMA (so no multiply-add is contracted), and nothing here uses approximate
// reciprocals. A kernel built from these therefore gives the same bits in both instantiations
// and as its scalar reference.
//
// Helpers are always inlined: a vector argument passed by value between functions of
// different targets would change the calling convention (hence the -Wpsabi note, silenced).

#include <cstdint>
#include <cstring>

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

typedef float F8 __attribute__((vector_size(32)));
typedef std::int32_t I8 __attribute__((vector_size(32)));
typedef std::uint32_t U8 __attribute__((vector_size(32)));
typedef double D4 __attribute__((vector_size(32)));
typedef float F4 __attribute__((vector_size(16)));
typedef std::uint8_t B8 __attribute__((vector_size(8)));
typedef std::uint16_t H8 __attribute__((vector_size(16)));

constexpr int kWidth = 8;  ///< floats per F8

/// Whether this processor runs AVX2 code (asked once; IGI_NO_AVX2=1 says no).
bool hasAvx2();

/// The code a kernel runs: eight lanes as SSE2 pairs (any x86-64) or as AVX2, the same bits.
enum class Isa { kBaseline, kAvx2 };
inline Isa bestIsa() {
    return hasAvx2() ? Isa::kAvx2 : Isa::kBaseline;
}

IGI_LANES F8 load(const float* p) {
    F8 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
IGI_LANES void store(float* p, F8 v) {
    std::memcpy(p, &v, sizeof v);
}
IGI_LANES D4 loadD4(const double* p) {
    D4 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
IGI_LANES void store(double* p, D4 v) {
    std::memcpy(p, &v, sizeof v);
}
/// Eight bytes, zero-extended to 32 bits each.
IGI_LANES U8 loadBytes(const std::uint8_t* p) {
    B8 v;
    std::memcpy(&v, p, sizeof v);
    return __builtin_convertvector(v, U8);
}

IGI_LANES F8 splat(float x) {
    return F8{x, x, x, x, x, x, x, x};
}
IGI_LANES D4 splat(double x) {
    return D4{x, x, x, x};
}
IGI_LANES I8 splat(std::int32_t x) {
    return I8{x, x, x, x, x, x, x, x};
}

/// mask ? a : b, lane by lane (mask lanes are all ones or all zeros, as comparisons give).
IGI_LANES F8 select(I8 mask, F8 a, F8 b) {
    return (F8)((mask & (I8)a) | (~mask & (I8)b));
}
IGI_LANES F8 abs(F8 a) {
    return (F8)((I8)a & splat(0x7FFFFFFF));
}
/// All ones where the lane is finite (not NaN, not +-inf).
IGI_LANES I8 finite(F8 a) {
    return ((I8)a & splat(0x7F800000)) != splat(0x7F800000);
}

#if IGI_HAS_AVX2_TARGET && !defined(__clang__)
// GCC 12 widens four floats to doubles two at a time through the stack; AVX has one
// instruction for it. Not inlined by force (a target mismatch would be an error where the
// kernel is instantiated for the baseline), but inlined where the AVX2 kernels call it.
IGI_AVX2 inline D4 widenAvx(F4 a) {
    return (D4)__builtin_ia32_cvtps2pd256(a);
}
#endif

/// Lanes 0-3 and 4-7 of a, as doubles (exact), and back (rounded as static_cast<float>).
/// `Avx2`: the caller is AVX2 code (IGI_AVX2).
template <bool Avx2 = false>
IGI_LANES D4 lowD4(F8 a) {
    const F4 low = __builtin_shufflevector(a, a, 0, 1, 2, 3);
#if IGI_HAS_AVX2_TARGET && !defined(__clang__)
    if constexpr (Avx2) return widenAvx(low);
#endif
    return __builtin_convertvector(low, D4);
}
template <bool Avx2 = false>
IGI_LANES D4 highD4(F8 a) {
    const F4 high = __builtin_shufflevector(a, a, 4, 5, 6, 7);
#if IGI_HAS_AVX2_TARGET && !defined(__clang__)
    if constexpr (Avx2) return widenAvx(high);
#endif
    return __builtin_convertvector(high, D4);
}
IGI_LANES F4 toF4(D4 a) {
    return __builtin_convertvector(a, F4);
}
IGI_LANES F8 join(F4 low, F4 high) {
    return __builtin_shufflevector(low, high, 0, 1, 2, 3, 4, 5, 6, 7);
}
IGI_LANES void store(float* p, F4 v) {
    std::memcpy(p, &v, sizeof v);
}

/// mask ? a : b for doubles; `mask` is a comparison of doubles (lanes all ones or zeros).
template <typename Mask>
IGI_LANES D4 select(Mask mask, D4 a, D4 b) {
    typedef std::int64_t L4 __attribute__((vector_size(32)));
    const L4 m = (L4)mask;
    return (D4)((m & (L4)a) | (~m & (L4)b));
}
/// std::max(a, b) lane by lane: (a < b) ? b : a, so a NaN in b gives a, as the scalar does.
IGI_LANES D4 stdMax(D4 a, D4 b) {
    return select(a < b, b, a);
}

}  // namespace igi::lanes

#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
