#include "sampling/Sobol.h"

#include <array>
#include <bit>

#include <boost/random/detail/sobol_table.hpp>

namespace igi {
namespace {

using Table = boost::random::detail::qrng_tables::sobol;
using DirectionNumbers = std::array<std::array<std::uint32_t, 32>, Sobol::kMaxDimensions>;

// Direction numbers v[d][j] = m_j << (31 - j), with m_j from the primitive polynomial of
// dimension d and its initial values (Bratley and Fox's recurrence, as in Boost's sobol_lattice).
DirectionNumbers makeDirectionNumbers() {
    DirectionNumbers v{};
    for (unsigned j = 0; j < 32; ++j) v[0][j] = 1u << (31 - j);
    for (unsigned d = 1; d < Sobol::kMaxDimensions; ++d) {
        const unsigned poly = Table::polynomial(d - 1);
        const unsigned degree = std::bit_width(poly) - 1;
        std::array<std::uint32_t, 32> m{};
        for (unsigned j = 0; j < degree && j < 32; ++j) m[j] = Table::minit(d - 1, j);
        for (unsigned j = degree; j < 32; ++j) {
            m[j] = m[j - degree];
            unsigned p = poly;
            for (unsigned k = 0; k < degree; ++k, p >>= 1) {
                const unsigned rem = degree - k;
                m[j] ^= ((p & 1u) * m[j - rem]) << rem;
            }
        }
        for (unsigned j = 0; j < 32; ++j) v[d][j] = m[j] << (31 - j);
    }
    return v;
}

const DirectionNumbers& directionNumbers() {
    static const DirectionNumbers table = makeDirectionNumbers();
    return table;
}

}  // namespace

std::uint32_t Sobol::sample(std::uint32_t index, unsigned dimension) {
    const auto& v = directionNumbers()[dimension];
    std::uint32_t result = 0;
    for (unsigned j = 0; index != 0; ++j, index >>= 1) {
        if (index & 1u) result ^= v[j];
    }
    return result;
}

}  // namespace igi
