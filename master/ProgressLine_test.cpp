#include "ProgressLine.h"

#include <gtest/gtest.h>

namespace igi {
namespace {

TEST(ProgressLine, SaysFramesRateTimeLeftAndClients) {
    EXPECT_EQ(ProgressLine::format(25, 100, 2.5, 2),
              "frame 25/100 [=====>              ] 2.50 fps, 30 s left, 2 clients");
    EXPECT_EQ(ProgressLine::format(100, 100, 4, 1),
              "frame 100/100 [====================] 4.00 fps, 0 s left, 1 client");
    // No rate yet: no estimate. Long runs count in minutes.
    EXPECT_EQ(ProgressLine::format(0, 10, 0, 3),
              "frame 0/10 [>                   ] 0.00 fps, ? left, 3 clients");
    EXPECT_EQ(ProgressLine::format(0, 1000, 2, 1),
              "frame 0/1000 [>                   ] 2.00 fps, 9 min left, 1 client");
    // A run that a target error or a time limit ends has no total.
    EXPECT_EQ(ProgressLine::format(7, 0, 2, 2), "frame 7 2.00 fps, 2 clients");
}

}  // namespace
}  // namespace igi
