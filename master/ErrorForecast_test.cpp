#include "ErrorForecast.h"

#include <gtest/gtest.h>

namespace igi {
namespace {

TEST(ErrorForecast, FitsOneOverFramesToTheLaterHalf) {
    ErrorForecast f;
    EXPECT_FALSE(f.coefficient());
    f.add(1, 5.0);  // one frame: no spread, ignored
    EXPECT_FALSE(f.coefficient());
    // A first stretch with a steeper fall (the first frame's bias), then 0.08 / frames.
    f.add(2, 0.2);
    f.add(3, 0.1);
    for (int n = 4; n <= 16; ++n) f.add(n, 0.08 / n);
    ASSERT_TRUE(f.coefficient());
    EXPECT_NEAR(*f.coefficient(), 0.08, 1e-12);
    EXPECT_NEAR(*f.framesTo(0.001), 80.0, 1e-9);
    EXPECT_NEAR(*f.secondsTo(0.001, 4.0), (80.0 - 16.0) / 4.0, 1e-9);
    EXPECT_FALSE(f.secondsTo(0.001, 0.0));  // no rate yet
    // A target already met is 0 s away and the frames in now.
    EXPECT_EQ(*f.secondsTo(0.01, 4.0), 0.0);
    EXPECT_EQ(*f.framesTo(0.01), 16.0);
    EXPECT_EQ(f.describe(0.001, 4.0), "est. relMSE 0.005 (target 0.001, ~16 s to it)");
    EXPECT_EQ(f.describe(0, 4.0), "est. relMSE 0.005");
    f.reset();
    EXPECT_EQ(f.describe(0.001, 4.0), "");
}

// A live session left on a still view: the forecast keeps a bounded number of points, and its
// fit is still that of the curve.
TEST(ErrorForecast, AMillionFramesKeepABoundedNumberOfPoints) {
    ErrorForecast f;
    for (int n = 2; n <= 1000000; ++n) f.add(n, 0.05 / n);
    EXPECT_LE(f.pointsKept(), ErrorForecast::kMaxPoints);
    ASSERT_TRUE(f.coefficient());
    EXPECT_NEAR(*f.coefficient(), 0.05, 1e-9);
    EXPECT_NEAR(*f.framesTo(1e-8), 5e6, 1e-3);
    EXPECT_EQ(f.describe(0, 1.0), "est. relMSE 5e-08");
}

}  // namespace
}  // namespace igi
