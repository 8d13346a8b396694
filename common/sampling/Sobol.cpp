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

const DirectionNumbers kDirections = makeDirectionNumbers();

// The low dimensions (light paths, photons, pixel positions: almost every sample) by bytes:
// point i is the XOR of four table entries, one per byte of i, instead of one entry per set
// bit behind an unpredictable branch. 8 x 4 x 256 entries: 32 kB.
constexpr unsigned kTabledDimensions = 8;
using ByteTables = std::array<std::array<std::array<std::uint32_t, 256>, 4>, kTabledDimensions>;

ByteTables makeByteTables() {
    ByteTables t{};
    for (unsigned d = 0; d < kTabledDimensions; ++d)
        for (unsigned byte = 0; byte < 4; ++byte)
            for (unsigned b = 0; b < 256; ++b) {
                std::uint32_t x = 0;
                for (unsigned j = 0; j < 8; ++j)
                    if (b & (1u << j)) x ^= kDirections[d][8 * byte + j];
                t[d][byte][b] = x;
            }
    return t;
}

const ByteTables kByteTables = makeByteTables();

}  // namespace

std::uint32_t Sobol::sample(std::uint32_t index, unsigned dimension) {
    if (dimension < kTabledDimensions) {
        const auto& t = kByteTables[dimension];
        return t[0][index & 0xFF] ^ t[1][(index >> 8) & 0xFF] ^ t[2][(index >> 16) & 0xFF] ^
               t[3][index >> 24];
    }
    const auto& v = kDirections[dimension];
    std::uint32_t result = 0;
    for (unsigned j = 0; index != 0; ++j, index >>= 1) {
        if (index & 1u) result ^= v[j];
    }
    return result;
}

}  // namespace igi
