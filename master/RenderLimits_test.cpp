#include "RenderLimits.h"

#include <gtest/gtest.h>

namespace igi {
namespace {

TEST(RenderLimits, FramesCountFromTheFirstFrameAndZeroRendersUntilStopped) {
    MasterOptions options;
    options.frames = 3;
    options.firstFrame = 10;
    RenderLimits limits(options);
    EXPECT_TRUE(limits.frameLeft(10));
    EXPECT_TRUE(limits.frameLeft(12));
    EXPECT_FALSE(limits.frameLeft(13));
    EXPECT_FALSE(limits.allFramesDone(2));
    EXPECT_TRUE(limits.allFramesDone(3));
    options.frames = 0;  // read when asked: an animation's length may set it after
    EXPECT_TRUE(limits.frameLeft(1000));
    EXPECT_FALSE(limits.allFramesDone(1000));
}

TEST(RenderLimits, NothingIsReachedBeforeTheStartAndTheClockRunsFromIt) {
    MasterOptions options;
    options.timeLimitSeconds = 1e-9;
    RenderLimits limits(options);
    EXPECT_FALSE(limits.started());
    EXPECT_EQ(limits.renderSeconds(), 0.0);
    EXPECT_FALSE(limits.timeUp());
    EXPECT_EQ(limits.reached(0), "");
    limits.start();
    EXPECT_TRUE(limits.timeUp());
    EXPECT_EQ(limits.reached(5), "--time-limit 1e-09 s reached after 5 frames");
    EXPECT_EQ(limits.json(1.0)["rendering"], "running");
}

TEST(RenderLimits, ALiveSessionIdlesAtItsLimitAndAnOtherEnds) {
    MasterOptions options;
    options.frames = 0;
    options.timeLimitSeconds = 1e-9;
    RenderLimits batch(options);
    batch.start();
    EXPECT_TRUE(batch.end("time up"));  // no control port, no view: the session ends
    EXPECT_FALSE(batch.idle());

    options.control = true;
    RenderLimits live(options);
    live.start();
    EXPECT_FALSE(live.end("time up"));
    EXPECT_TRUE(live.idle());
    EXPECT_FALSE(live.frameLeft(0));
    EXPECT_FALSE(live.timeUp());  // idle: nothing more to end
    EXPECT_EQ(live.reached(1), "");
    EXPECT_EQ(live.json(1.0)["rendering"], "idle");
    // The clock stopped when it went idle.
    const double idleAt = live.renderSeconds();
    EXPECT_EQ(live.renderSeconds(), idleAt);
    // Time up is up for good, even after a change.
    EXPECT_FALSE(live.resume(true));
    EXPECT_TRUE(live.idle());
}

TEST(RenderLimits, AChangeResumesAnIdleSessionUnlessItEnds) {
    MasterOptions options;
    options.frames = 0;
    options.view = true;
    RenderLimits limits(options);
    limits.start();
    EXPECT_FALSE(limits.resume(true));  // not idle: nothing to resume
    EXPECT_FALSE(limits.end("target met"));
    ASSERT_TRUE(limits.idle());
    EXPECT_TRUE(limits.resume(true));
    EXPECT_FALSE(limits.idle());
    EXPECT_TRUE(limits.frameLeft(7));

    EXPECT_FALSE(limits.end("target met"));
    limits.sessionEnds();
    EXPECT_FALSE(limits.resume(true));  // a session that ends does not render again
}

}  // namespace
}  // namespace igi
