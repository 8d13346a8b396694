#include "image/ImageCompare.h"

#include <gtest/gtest.h>

namespace igi {
namespace {

Image ramp(int w, int h, float scale) {
    Image im(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) im.at(x, y) = glm::vec3(scale * float(x + y) / float(w + h));
    return im;
}

TEST(ImageCompare, IdenticalImagesHaveNoError) {
    const Image a = ramp(32, 24, 1.0f);
    const ImageDifference d = compareImages(a, a);
    EXPECT_EQ(d.relativeMse, 0.0);
    EXPECT_EQ(d.rmse, 0.0);
    EXPECT_EQ(d.meanRelativeBias, 0.0);
    EXPECT_EQ(d.blockRelativeError, 0.0);
    EXPECT_NEAR(d.ssim, 1.0, 1e-12);
}

TEST(ImageCompare, ABrighterImageShowsItsBias) {
    const ImageDifference d = compareImages(ramp(32, 24, 1.1f), ramp(32, 24, 1.0f));
    EXPECT_NEAR(d.meanRelativeBias, 0.1, 1e-5);
    EXPECT_NEAR(d.blockRelativeError, 0.1, 1e-5);
    EXPECT_GT(d.relativeMse, 0.0);
    EXPECT_LT(d.ssim, 1.0);
}

TEST(ImageCompare, NoiseLowersSsimMoreThanASmallBias) {
    Image noisy = ramp(64, 64, 1.0f);
    for (std::size_t i = 0; i < noisy.pixels.size(); ++i) noisy.pixels[i] *= (i % 2 ? 1.3f : 0.7f);
    const Image biased = ramp(64, 64, 1.02f), reference = ramp(64, 64, 1.0f);
    EXPECT_LT(compareImages(noisy, reference).ssim, compareImages(biased, reference).ssim);
    EXPECT_NEAR(compareImages(noisy, reference).blockRelativeError, 0.0,
                0.01);  // noise averages out
}

TEST(ImageCompare, DifferentSizesAreRefused) {
    EXPECT_THROW(compareImages(Image(2, 2), Image(3, 2)), std::invalid_argument);
}

}  // namespace
}  // namespace igi
