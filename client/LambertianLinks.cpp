#include "LambertianLinks.h"

#include <bit>

#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wpsabi"  // the kernels' vectors never cross a call (Lanes.h)
#endif

namespace igi {
namespace {

using lanes::F4;
using lanes::F8;
using lanes::Isa;

template <class V>
IGI_LANES std::size_t linksBody(const VplChoice& l, std::size_t count, glm::vec3 origin,
                                glm::vec3 n, glm::vec3 f, float dmin2, LambertianLink* out) {
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
        for (; bits != 0; bits &= bits - 1) {
            const int i = std::countr_zero(bits);
            out[links++] = {std::uint32_t(j) + std::uint32_t(i), d[i], {wx[i], wy[i], wz[i]}, g[i]};
        }
    }
    return links;
}

std::size_t linksBaseline(const VplChoice& l, std::size_t count, glm::vec3 origin, glm::vec3 n,
                          glm::vec3 f, float dmin2, LambertianLink* out) {
    return linksBody<F4>(l, count, origin, n, f, dmin2, out);
}

#if IGI_HAS_AVX2_TARGET
IGI_AVX2 std::size_t linksAvx2(const VplChoice& l, std::size_t count, glm::vec3 origin, glm::vec3 n,
                               glm::vec3 f, float dmin2, LambertianLink* out) {
    return linksBody<F8>(l, count, origin, n, f, dmin2, out);
}
#endif

}  // namespace

std::size_t lambertianLinks(const VplChoice& vpls, std::size_t count, glm::vec3 origin, glm::vec3 n,
                            glm::vec3 f, float dmin2, LambertianLink* out, Isa isa) {
#if IGI_HAS_AVX2_TARGET
    if (isa == Isa::kAvx2) return linksAvx2(vpls, count, origin, n, f, dmin2, out);
#endif
    return linksBaseline(vpls, count, origin, n, f, dmin2, out);
}

}  // namespace igi
