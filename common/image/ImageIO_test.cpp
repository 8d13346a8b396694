#include "image/ImageIO.h"
#include "util/TestPaths.h"

#include <filesystem>

#include <gtest/gtest.h>

namespace igi {
namespace {

TEST(ImageIO, ExrRoundTripsLinearValuesIncludingLargeOnes) {
    Image image(3, 2);
    image.at(0, 0) = glm::vec3(0.25f, 1e6f, 1e-6f);
    image.at(2, 1) = glm::vec3(123.5f, 0, 7);
    const auto path = testing::scratchPath("imageio.exr");
    writeImage(path, image);
    const Image back = readImage(path);
    ASSERT_EQ(back.width, 3);
    ASSERT_EQ(back.height, 2);
    EXPECT_FLOAT_EQ(back.at(0, 0).y, 1e6f);
    EXPECT_FLOAT_EQ(back.at(0, 0).z, 1e-6f);
    EXPECT_FLOAT_EQ(back.at(2, 1).x, 123.5f);
    std::filesystem::remove(path);
}

TEST(ImageIO, PngIsToneMappedSrgbAndClipped) {
    Image image(2, 1);
    image.at(0, 0) = glm::vec3(0.5f, 2.0f, 0.0f);
    image.at(1, 0) = glm::vec3(0.25f);
    const auto path = testing::scratchPath("imageio.png");
    writeImage(path, image, 1.0f);  // one stop up: 0.5 -> 1.0, 0.25 -> 0.5
    const Image back = readImage(path);
    EXPECT_NEAR(back.at(0, 0).x, 1.0f, 1e-3f);
    EXPECT_NEAR(back.at(0, 0).y, 1.0f, 1e-3f);
    EXPECT_NEAR(back.at(1, 0).x, 0.5f, 5e-3f);  // 8-bit sRGB quantization
    std::filesystem::remove(path);
}

TEST(ImageIO, UnknownExtensionAndUnreadableFileAreErrors) {
    EXPECT_THROW(writeImage("/tmp/igi_x.unknownformat", Image(1, 1)), std::runtime_error);
    EXPECT_THROW(readImage("/nonexistent/igi.png"), std::runtime_error);
}

}  // namespace
}  // namespace igi
