#include "ImageSize.h"

#include <gtest/gtest.h>

namespace igi {
namespace {

void expectSize(ImageSize got, int width, int height) {
    EXPECT_EQ(got.width, width);
    EXPECT_EQ(got.height, height);
}

// Issue 40: --width 160 alone gave 160 x 480 of a 640 x 480 scene.
TEST(ImageSize, OneEdgeGivenKeepsTheScenesAspectRatio) {
    expectSize(overriddenImageSize({640, 480}, 160, 0), 160, 120);
    expectSize(overriddenImageSize({640, 480}, 0, 120), 160, 120);
    expectSize(overriddenImageSize({640, 480}, 101, 0), 101, 76);  // 75.75 rounded
    expectSize(overriddenImageSize({1000, 1}, 10, 0), 10, 1);      // never 0 pixels
    expectSize(overriddenImageSize({1, 1000}, 0, 16384, 16384), 16, 16384);
    expectSize(overriddenImageSize({10, 1000}, 16384, 0, 16384), 16384, 16384);  // capped
}

TEST(ImageSize, BothOrNeitherGiven) {
    expectSize(overriddenImageSize({640, 480}, 100, 100), 100, 100);
    expectSize(overriddenImageSize({640, 480}, 0, 0), 640, 480);
}

}  // namespace
}  // namespace igi
