#include "sampling/Distribution1D.h"

#include <gtest/gtest.h>

namespace igi {
namespace {

TEST(Distribution1D, ChoosesInProportionAndNeverAZeroWeight) {
    const Distribution1D d({1.0f, 0.0f, 3.0f, 0.0f});
    EXPECT_FLOAT_EQ(d.pdf(0), 0.25f);
    EXPECT_FLOAT_EQ(d.pdf(2), 0.75f);
    int counts[4] = {};
    const int n = 4000;
    for (int i = 0; i < n; ++i) ++counts[d.sample((i + 0.5f) / n)];
    EXPECT_EQ(counts[1], 0);
    EXPECT_EQ(counts[3], 0);
    EXPECT_EQ(counts[0], 1000);
    EXPECT_EQ(counts[2], 3000);
    EXPECT_EQ(d.sample(0x1.fffffep-1f),
              2u);  // the end of the range maps to the last non-zero entry
}

TEST(Distribution1D, RemappedValueIsUniformWithinTheEntry) {
    const Distribution1D d({1.0f, 1.0f});
    float r = -1;
    EXPECT_EQ(d.sample(0.25f, &r), 0u);
    EXPECT_FLOAT_EQ(r, 0.5f);
    EXPECT_EQ(d.sample(0.75f, &r), 1u);
    EXPECT_FLOAT_EQ(r, 0.5f);
}

TEST(Distribution1D, AllZeroIsEmpty) {
    EXPECT_TRUE(Distribution1D({0.0f, 0.0f}).empty());
    EXPECT_TRUE(Distribution1D(std::vector<float>{}).empty());
}

}  // namespace
}  // namespace igi
