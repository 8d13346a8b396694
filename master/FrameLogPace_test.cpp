#include "FrameLogPace.h"

#include <gtest/gtest.h>

namespace igi {
namespace {

// Issue 40, item 9: a live session at 100 fps logged 100 frame lines a second.
TEST(FrameLogPace, OneLineASecondWithTheFramesBetweenCounted) {
    FrameLogPace pace;
    int lines = 0;
    for (int frame = 0; frame < 500; ++frame) lines += pace.due(frame / 100.0);  // 100 fps, 5 s
    EXPECT_EQ(lines, 5);
    EXPECT_EQ(pace.skippedBefore(), 99);
    EXPECT_TRUE(pace.due(10.0));
    EXPECT_EQ(pace.skippedBefore(), 99) << "frames 401 to 499";
}

TEST(FrameLogPace, SlowFramesAllGetTheirLine) {
    FrameLogPace pace;
    for (int frame = 0; frame < 5; ++frame) EXPECT_TRUE(pace.due(frame * 1.5));
    EXPECT_EQ(pace.skippedBefore(), 0);
}

}  // namespace
}  // namespace igi
