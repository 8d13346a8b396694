#include "image/JpegEncoder.h"

#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "image/ImageIO.h"
#include "image/ToneMap.h"

namespace igi {
namespace {

// The encoded bytes are a JPEG file that a decoder reads back as the tone-mapped image, within
// JPEG's loss; the exposure is applied.
TEST(JpegEncoder, DecodesToTheToneMappedImage) {
    Image image(96, 64);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            image.at(x, y) = glm::vec3(x / 96.0f, y / 64.0f, 0.25f);
    for (float exposure : {0.0f, 1.0f}) {
        const std::string jpeg = encodeJpeg(image, exposure, 90);
        ASSERT_GT(jpeg.size(), 100u);
        EXPECT_EQ(static_cast<unsigned char>(jpeg[0]), 0xFF);
        EXPECT_EQ(static_cast<unsigned char>(jpeg[1]), 0xD8);
        const auto path = std::filesystem::path(::testing::TempDir()) / "jpeg_encoder_test.jpg";
        std::ofstream(path, std::ios::binary).write(jpeg.data(), std::streamsize(jpeg.size()));
        const Image decoded = readImage(path);  // linear again, from sRGB
        ASSERT_EQ(decoded.width, image.width);
        ASSERT_EQ(decoded.height, image.height);
        const std::vector<std::uint8_t> expected = toneMap8(image, exposure);
        double error = 0;
        for (std::size_t i = 0; i < decoded.pixels.size(); ++i)
            for (int c = 0; c < 3; ++c)
                error += std::abs(255.0 * linearToSrgb(decoded.pixels[i][c]) - expected[3 * i + c]);
        error /= 3.0 * decoded.pixels.size();
        EXPECT_LT(error, 2.0) << "mean error in 8-bit levels, exposure " << exposure;
    }
}

}  // namespace
}  // namespace igi
