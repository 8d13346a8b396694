#include "sampling/Sobol.h"

#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "sampling/Scramble.h"

namespace igi {
namespace {

// Points 0..7 of dimensions 0..3 in natural order (docs: ../shared/DESIGN.md).
TEST(Sobol, NaturalOrderMatchesKnownPoints) {
    const double expected[4][8] = {
        {0, .5, .25, .75, .125, .625, .375, .875},
        {0, .5, .75, .25, .625, .125, .375, .875},
        {0, .5, .75, .25, .375, .875, .625, .125},
        {0, .5, .75, .25, .125, .625, .875, .375},
    };
    for (unsigned d = 0; d < 4; ++d)
        for (unsigned i = 0; i < 8; ++i)
            EXPECT_EQ(Sobol::toFloat(Sobol::sample(i, d)), expected[d][i])
                << "dimension " << d << " point " << i;
}

// Every elementary interval of area 2^-m of [0,1)^2 holds exactly one of the first 2^m points
// of dimensions 0 and 1 (a (0, 2)-sequence), and an XOR scramble keeps that true.
void expectOnePointPerElementaryInterval(std::uint32_t scramble0, std::uint32_t scramble1,
                                         std::uint32_t first) {
    for (unsigned m = 1; m <= 10; ++m) {
        const std::uint32_t count = 1u << m;
        for (unsigned a = 0; a <= m; ++a) {  // intervals 2^-a wide, 2^-(m-a) high
            std::set<std::pair<std::uint32_t, std::uint32_t>> cells;
            for (std::uint32_t i = first; i < first + count; ++i) {
                const std::uint32_t x = Sobol::sample(i, 0) ^ scramble0,
                                    y = Sobol::sample(i, 1) ^ scramble1;
                const std::uint32_t cx = a == 0 ? 0 : x >> (32 - a);
                const std::uint32_t cy = m - a == 0 ? 0 : y >> (32 - (m - a));
                cells.insert({cx, cy});
            }
            EXPECT_EQ(cells.size(), count) << "m=" << m << " a=" << a << " first=" << first;
        }
    }
}

TEST(Sobol, ScrambledPointsStayOnePerElementaryInterval) {
    expectOnePointPerElementaryInterval(0, 0, 0);
    for (std::uint32_t frame = 0; frame < 4; ++frame)
        expectOnePointPerElementaryInterval(scrambleBits(7, frame, SampleStream::VplPaths, 0),
                                            scrambleBits(7, frame, SampleStream::VplPaths, 1), 0);
    // A block aligned at a multiple of its size is a net too: the subsequence of a set k.
    expectOnePointPerElementaryInterval(0x12345678u, 0x9abcdef0u, 1024);
}

TEST(Sobol, NoSampleEqualsOne) {
    EXPECT_LT(Sobol::toFloat(0xFFFFFFFFu), 1.0f);
    EXPECT_LT(Sobol::toFloat(0xFFFFFF80u), 1.0f);
    for (std::uint32_t i = 0; i < 4096; ++i)
        for (unsigned d = 0; d < 8; ++d) {
            const float v = Sobol::scrambled(i, d, 0xFFFFFFFFu);
            ASSERT_GE(v, 0.0f);
            ASSERT_LT(v, 1.0f);
        }
}

TEST(Sobol, HigherDimensionsAreStratifiedInOneDimension) {
    // Each one-dimensional projection of the first 2^m points hits every interval of 2^-m once.
    for (unsigned d = 0; d < Sobol::kMaxDimensions; d += 17) {
        std::set<std::uint32_t> cells;
        for (std::uint32_t i = 0; i < 256; ++i) cells.insert(Sobol::sample(i, d) >> 24);
        EXPECT_EQ(cells.size(), 256u) << "dimension " << d;
    }
}

TEST(Scramble, SameInputsSameBitsDifferentFramesDifferentBits) {
    EXPECT_EQ(scrambleBits(1, 5, SampleStream::VplPaths, 3),
              scrambleBits(1, 5, SampleStream::VplPaths, 3));
    EXPECT_NE(scrambleBits(1, 5, SampleStream::VplPaths, 3),
              scrambleBits(1, 6, SampleStream::VplPaths, 3));
    EXPECT_NE(scrambleBits(1, 5, SampleStream::VplPaths, 3),
              scrambleBits(2, 5, SampleStream::VplPaths, 3));
    EXPECT_NE(scrambleBits(1, 5, SampleStream::VplPaths, 3),
              scrambleBits(1, 5, SampleStream::DirectLight, 3));
}

}  // namespace
}  // namespace igi
