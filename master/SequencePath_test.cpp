#include "SequencePath.h"

#include <gtest/gtest.h>

namespace igi {
namespace {

TEST(SequencePath, FormatsTheFrameNumber) {
    EXPECT_EQ(sequencePath("out/frame_%04d.png", 7), "out/frame_0007.png");
    EXPECT_EQ(sequencePath("f%d.exr", 12345), "f12345.exr");
    EXPECT_EQ(sequencePath("100%%_%03d.png", 5), "100%_005.png");
    EXPECT_NO_THROW(checkSequencePattern("out/frame_%04d.png"));
}

TEST(SequencePath, RefusesPatternsThatCouldMisbehave) {
    EXPECT_THROW(checkSequencePattern("out/frame.png"), std::invalid_argument);  // no number
    EXPECT_THROW(checkSequencePattern("out/%d_%d.png"), std::invalid_argument);  // two
    EXPECT_THROW(checkSequencePattern("out/%s.png"), std::invalid_argument);     // not %d
    EXPECT_THROW(checkSequencePattern("out/%999d.png"), std::invalid_argument);  // silly width
    EXPECT_THROW(checkSequencePattern("out/%04d.jpg"), std::invalid_argument);   // format
}

}  // namespace
}  // namespace igi
