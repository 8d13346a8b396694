#include "sampling/LightPathSampler.h"

#include <algorithm>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "sampling/Sobol.h"

namespace igi {
namespace {

TEST(LightPathSampler, SetsAreConsecutiveBlocksOfOneSequence) {
    // Emission samples of set k, path j are point k*N + j of one scrambled sequence.
    const std::uint32_t n = 12;
    const LightPathSampler set0(3, 9, SampleStream::VplPaths, 0, n, 4);
    const LightPathSampler set2(3, 9, SampleStream::VplPaths, 2, n, 4);
    const std::uint32_t scramble = scrambleBits(3, 9, SampleStream::VplPaths, 1);
    for (std::uint32_t j = 0; j < n; ++j) {
        EXPECT_EQ(set0.emission(j, 1), Sobol::scrambled(j, 1, scramble));
        EXPECT_EQ(set2.emission(j, 1), Sobol::scrambled(2 * n + j, 1, scramble));
    }
}

TEST(LightPathSampler, EachBounceReplicatesTheSetsPointsInSomeOrder) {
    // Padded replications: the bounce samples of a set are the same points as the set's own
    // (in dimension d, up to the bounce's XOR), each used once.
    const std::uint32_t n = 64;
    const LightPathSampler s(11, 3, SampleStream::CausticPhotons, 5, n, 6);
    for (unsigned bounce = 1; bounce <= 6; ++bounce) {
        std::multiset<std::uint32_t> seen, expected;
        for (std::uint32_t j = 0; j < n; ++j) {
            const float v = s.bounce(j, bounce, 0);
            ASSERT_GE(v, 0.0f);
            ASSERT_LT(v, 1.0f);
            seen.insert(std::uint32_t(v * 64.0f));  // which of 64 strata
        }
        // 64 consecutive aligned Sobol' points stratify [0,1) in 64 intervals: one each.
        for (std::uint32_t c = 0; c < 64; ++c) expected.insert(c);
        EXPECT_EQ(seen, expected) << "bounce " << bounce;
    }
}

TEST(LightPathSampler, DeterministicAndDecorrelatedAcrossBounces) {
    const LightPathSampler a(1, 2, SampleStream::VplPaths, 3, 32, 4),
        b(1, 2, SampleStream::VplPaths, 3, 32, 4);
    int same = 0;
    for (std::uint32_t j = 0; j < 32; ++j) {
        EXPECT_EQ(a.bounce(j, 2, 1), b.bounce(j, 2, 1));
        same += a.bounce(j, 1, 0) == a.bounce(j, 2, 0);
    }
    EXPECT_LT(same, 4);  // different permutations and scrambles per bounce
}

}  // namespace
}  // namespace igi
