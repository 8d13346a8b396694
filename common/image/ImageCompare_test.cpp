#include "image/ImageCompare.h"

#include <cmath>

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

Image grey(int w, int h, float value) {
    Image im(w, h);
    for (auto& p : im.pixels) p = glm::vec3(value);
    return im;
}

TEST(ImageCompare, AnImageEqualToTheReferenceHasNoSpeckle) {
    const Image a = ramp(32, 24, 1.0f);
    EXPECT_EQ(compareImages(a, a).speckle, 0.0);
    // Uniformly brighter, but not by more than 4x: no speckle either.
    EXPECT_EQ(compareImages(ramp(32, 24, 3.9f), a).speckle, 0.0);
}

TEST(ImageCompare, OnePixelAtFiveTimesTheReferenceIsOneCountedPixel) {
    const Image reference = grey(10, 10, 0.5f);
    Image image = reference;
    image.at(3, 7) = glm::vec3(2.5f);
    EXPECT_DOUBLE_EQ(compareImages(image, reference).speckle, 1.0 / 100.0);
    image.at(9, 0) = glm::vec3(0.0f, 5.0f, 0.0f);  // luminance 3.576: more than 4 x 0.5
    EXPECT_DOUBLE_EQ(compareImages(image, reference).speckle, 2.0 / 100.0);
    // Luminance, not a channel: 9 times the reference in blue alone (0.0722 x 4.5 < 4 x 0.5).
    image.at(5, 5) = glm::vec3(0.5f, 0.5f, 4.5f);
    EXPECT_DOUBLE_EQ(compareImages(image, reference).speckle, 2.0 / 100.0);
    // Darker pixels are not speckle.
    image.at(1, 1) = glm::vec3(0.0f);
    EXPECT_DOUBLE_EQ(compareImages(image, reference).speckle, 2.0 / 100.0);
}

TEST(ImageCompare, SpeckleIgnoresPixelsTheReferenceBarelyLights) {
    // 20 pixels, 4 of them at 1e-4: the mean is 0.8, the threshold 0.008.
    Image reference = grey(5, 4, 1.0f);
    for (int x = 0; x < 4; ++x) reference.at(x, 0) = glm::vec3(1e-4f);
    Image image = reference;
    image.at(0, 0) = glm::vec3(5e-4f);  // 5x, but where the reference is below 1% of the mean
    image.at(1, 0) = glm::vec3(1.0f);   // 10000x, likewise
    EXPECT_EQ(compareImages(image, reference).speckle, 0.0);
    image.at(2, 2) = glm::vec3(5.0f);  // one of the 16 counted pixels
    EXPECT_DOUBLE_EQ(compareImages(image, reference).speckle, 1.0 / 16.0);
}

TEST(ImageCompare, SpeckleThresholdIsOnePercentOfTheReferenceMean) {
    // 100 pixels, 98 of them at 1: the mean luminance is about 0.98, 1% of it 0.0098.
    Image reference = grey(10, 10, 1.0f);
    reference.at(0, 0) = glm::vec3(0.0105f);  // above 1% of the mean: counted
    reference.at(1, 0) = glm::vec3(0.0095f);  // below: ignored
    Image image = reference;
    image.at(0, 0) *= 5.0f;
    image.at(1, 0) *= 5.0f;
    EXPECT_DOUBLE_EQ(compareImages(image, reference).speckle, 1.0 / 99.0);
    // Black reference pixels are always ignored, however bright the image is there.
    reference.at(2, 0) = image.at(2, 0) = glm::vec3(0.0f);
    image.at(2, 0) = glm::vec3(1.0f);
    EXPECT_DOUBLE_EQ(compareImages(image, reference).speckle, 1.0 / 98.0);
}

TEST(ImageCompare, ExactlyFourTimesTheReferenceIsNotSpeckle) {
    const Image reference = grey(8, 8, 0.25f);
    Image image = reference;
    image.at(2, 3) = glm::vec3(1.0f);  // exactly 4 x 0.25 (powers of two: no rounding)
    EXPECT_EQ(compareImages(image, reference).speckle, 0.0);
    image.at(2, 3) = glm::vec3(std::nextafter(1.0f, 2.0f));  // just above
    EXPECT_DOUBLE_EQ(compareImages(image, reference).speckle, 1.0 / 64.0);
}

TEST(ImageCompare, ABlackReferenceHasNoSpeckle) {
    EXPECT_EQ(compareImages(grey(4, 4, 1.0f), grey(4, 4, 0.0f)).speckle, 0.0);
}

TEST(ImageCompare, DifferentSizesAreRefused) {
    EXPECT_THROW(compareImages(Image(2, 2), Image(3, 2)), std::invalid_argument);
}

}  // namespace
}  // namespace igi
