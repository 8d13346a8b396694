#include "ProgressLine.h"

#include <cstdio>

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

std::string contentsOf(std::FILE* f) {
    std::fflush(f);
    std::rewind(f);
    std::string text;
    for (int c; (c = std::fgetc(f)) != EOF;) text.push_back(char(c));
    return text;
}

// A local client's stderr line prints above the progress line, which is then drawn again:
// never into it.
TEST(ProgressLine, AClientsLinePrintsAboveTheLineAndTheLineIsDrawnAgain) {
    std::FILE* out = std::tmpfile();
    ASSERT_NE(out, nullptr);
    {
        ProgressLine line(10, out);
        line.update(2, 1.0, 1);
        line.printAbove("[client] [warning] slow disk");
        line.finish();
    }
    const std::string bar = "frame 2/10 [====>               ] 1.00 fps, 8 s left, 1 client";
    EXPECT_EQ(contentsOf(out),
              "\r\033[K" + bar + "\r\033[K[client] [warning] slow disk\n" + bar + "\n");
    std::fclose(out);
}

}  // namespace
}  // namespace igi
