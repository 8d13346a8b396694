#include "lighting/LambertianLinks.h"

#include <array>
#include <bit>

#if IGI_HAS_AVX2_TARGET
#include <immintrin.h>
#endif

#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wpsabi"  // the kernels' vectors never cross a call (Lanes.h)
#endif

namespace igi {

/// The arrays of a LinkBuffer, for the kernels to write.
struct LinkWriter {
    std::uint32_t* vpl;
    float *d, *wx, *wy, *wz, *g;
    explicit LinkWriter(LinkBuffer& b)
        : vpl(b.vpl_.data()),
          d(b.d_.data()),
          wx(b.wx_.data()),
          wy(b.wy_.data()),
          wz(b.wz_.data()),
          g(b.g_.data()) {}
    static std::size_t finish(LinkBuffer& b, std::size_t size) { return b.size_ = size; }
};

void LinkBuffer::reserve(std::size_t count) {
    const std::size_t room = count + 8;
    if (vpl_.size() >= room) return;
    vpl_.resize(room);
    for (auto* v : {&d_, &wx_, &wy_, &wz_, &g_}) v->resize(room);
}

namespace {

using lanes::F4;
using lanes::F8;
using lanes::Isa;

#if IGI_HAS_AVX2_TARGET
// Entry m: the lanes whose bit is set in m, in increasing order, one byte each (then zeros).
constexpr std::array<std::uint64_t, 256> kPackLeft = [] {
    std::array<std::uint64_t, 256> table{};
    for (unsigned m = 0; m < 256; ++m)
        for (unsigned i = 0, k = 0; i < 8; ++i)
            if (m >> i & 1u) table[m] |= std::uint64_t(i) << (8 * k++);
    return table;
}();

// Writes the lanes of `bits` (indices j .. j + 7) packed to the front of the writer's arrays at
// `at`: eight lanes per store (the buffer has a lane group of room beyond its VPLs).
IGI_AVX2 inline void storePacked(unsigned bits, std::uint32_t j, F8 d, F8 wx, F8 wy, F8 wz, F8 g,
                                 const LinkWriter& out, std::size_t at) {
    const __m256i order =
        _mm256_cvtepu8_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(&kPackLeft[bits])));
    const __m256i index = _mm256_add_epi32(_mm256_set1_epi32(std::int32_t(j)),
                                           _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out.vpl + at),
                        _mm256_permutevar8x32_epi32(index, order));
    _mm256_storeu_ps(out.d + at, _mm256_permutevar8x32_ps(__m256(d), order));
    _mm256_storeu_ps(out.wx + at, _mm256_permutevar8x32_ps(__m256(wx), order));
    _mm256_storeu_ps(out.wy + at, _mm256_permutevar8x32_ps(__m256(wy), order));
    _mm256_storeu_ps(out.wz + at, _mm256_permutevar8x32_ps(__m256(wz), order));
    _mm256_storeu_ps(out.g + at, _mm256_permutevar8x32_ps(__m256(g), order));
}
#endif

template <class V>
IGI_LANES std::size_t linksBody(const VplChoice& l, std::size_t count, glm::vec3 origin,
                                glm::vec3 n, glm::vec3 f, float dmin2, const LinkWriter& out) {
    constexpr int kWidth = lanes::kLanes<V>;
    using lanes::load;
    using lanes::splat;
    const V ox = splat<V>(origin.x), oy = splat<V>(origin.y), oz = splat<V>(origin.z);
    const V m2 = splat<V>(dmin2), zero = splat<V>(0.0f);
    std::size_t links = 0;
    for (std::size_t j = 0; j < count; j += kWidth) {
        const V tx = load<V>(&l.px[j]) - ox, ty = load<V>(&l.py[j]) - oy,
                tz = load<V>(&l.pz[j]) - oz;
        const V d2 = tx * tx + ty * ty + tz * tz;
        const V d = lanes::squareRoot(d2);
        const V wx = tx / d, wy = ty / d, wz = tz / d;
        const V cosX = splat<V>(n.x) * wx + splat<V>(n.y) * wy + splat<V>(n.z) * wz;
        const V face = splat<V>(f.x) * wx + splat<V>(f.y) * wy + splat<V>(f.z) * wz;
        const V cosY =
            zero - (load<V>(&l.nx[j]) * wx + load<V>(&l.ny[j]) * wy + load<V>(&l.nz[j]) * wz);
        const V g = cosX * cosY / lanes::stdMax(d2, m2);
        // The scalar tests, negated as there: a NaN cosine is not rejected, a NaN d2 is.
        const auto kept = (d2 > zero) & ~(cosX <= zero) & ~(face <= zero) & ~(cosY <= zero);
        std::uint32_t bits = lanes::laneBits(kept);
        if (l.anyGeneral) {
            bits |= l.generalBits(j);
            if constexpr (kWidth == 8) bits |= l.generalBits(j + 4) << 4;
        }
        if (j + kWidth > count) bits &= (1u << (count - j)) - 1u;
#if IGI_HAS_AVX2_TARGET
        if constexpr (kWidth == 8) {
            storePacked(bits, std::uint32_t(j), d, wx, wy, wz, g, out, links);
            links += std::size_t(std::popcount(bits));
            continue;
        }
#endif
        for (; bits != 0; bits &= bits - 1) {
            const int i = std::countr_zero(bits);
            out.vpl[links] = std::uint32_t(j) + std::uint32_t(i);
            out.d[links] = d[i];
            out.wx[links] = wx[i];
            out.wy[links] = wy[i];
            out.wz[links] = wz[i];
            out.g[links] = g[i];
            ++links;
        }
    }
    return links;
}

std::size_t linksBaseline(const VplChoice& l, std::size_t count, glm::vec3 origin, glm::vec3 n,
                          glm::vec3 f, float dmin2, const LinkWriter& out) {
    return linksBody<F4>(l, count, origin, n, f, dmin2, out);
}

#if IGI_HAS_AVX2_TARGET
IGI_AVX2 std::size_t linksAvx2(const VplChoice& l, std::size_t count, glm::vec3 origin, glm::vec3 n,
                               glm::vec3 f, float dmin2, const LinkWriter& out) {
    return linksBody<F8>(l, count, origin, n, f, dmin2, out);
}
#endif

}  // namespace

std::size_t lambertianLinks(const VplChoice& vpls, std::size_t count, glm::vec3 origin, glm::vec3 n,
                            glm::vec3 f, float dmin2, LinkBuffer& out, Isa isa) {
    out.reserve(count);
    const LinkWriter writer(out);
#if IGI_HAS_AVX2_TARGET
    if (isa == Isa::kAvx2)
        return LinkWriter::finish(out, linksAvx2(vpls, count, origin, n, f, dmin2, writer));
#endif
    return LinkWriter::finish(out, linksBaseline(vpls, count, origin, n, f, dmin2, writer));
}

}  // namespace igi
