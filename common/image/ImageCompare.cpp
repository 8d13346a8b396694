#include "image/ImageCompare.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "image/ToneMap.h"
#include "math/Color.h"

namespace igi {
namespace {

// Display luminance in [0, 1], the domain SSIM's constants are made for.
std::vector<double> displayLuminance(const Image& image, float exposure) {
    const float scale = std::exp2(exposure);
    std::vector<double> y(image.pixels.size());
    for (std::size_t i = 0; i < y.size(); ++i)
        y[i] = linearToSrgb(luminance(image.pixels[i]) * scale);
    return y;
}

// Mean SSIM over 8 x 8 windows with stride 4 (Wang et al. 2004, uniform window).
double ssim(const Image& a, const Image& b, float exposure) {
    const auto x = displayLuminance(a, exposure), y = displayLuminance(b, exposure);
    constexpr double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
    constexpr int window = 8, stride = 4;
    double sum = 0;
    int count = 0;
    for (int y0 = 0; y0 + window <= a.height; y0 += stride) {
        for (int x0 = 0; x0 + window <= a.width; x0 += stride) {
            double mx = 0, my = 0, vx = 0, vy = 0, cov = 0;
            for (int j = 0; j < window; ++j)
                for (int i = 0; i < window; ++i) {
                    const std::size_t p = std::size_t(y0 + j) * a.width + x0 + i;
                    mx += x[p];
                    my += y[p];
                }
            const double n = window * window;
            mx /= n;
            my /= n;
            for (int j = 0; j < window; ++j)
                for (int i = 0; i < window; ++i) {
                    const std::size_t p = std::size_t(y0 + j) * a.width + x0 + i;
                    vx += (x[p] - mx) * (x[p] - mx);
                    vy += (y[p] - my) * (y[p] - my);
                    cov += (x[p] - mx) * (y[p] - my);
                }
            vx /= n - 1;
            vy /= n - 1;
            cov /= n - 1;
            sum +=
                ((2 * mx * my + c1) * (2 * cov + c2)) / ((mx * mx + my * my + c1) * (vx + vy + c2));
            ++count;
        }
    }
    return count > 0 ? sum / count : 1.0;
}

// The fraction of the pixels the reference lights enough (luminance at least
// kSpeckleMinReference of its mean) where the image is more than kSpeckleRatio times as bright.
double speckle(const Image& image, const Image& reference) {
    double sum = 0;
    for (const glm::vec3& p : reference.pixels) sum += luminance(p);
    if (reference.pixels.empty() || !(sum > 0)) return 0;  // nothing lit to compare with
    const double threshold = kSpeckleMinReference * sum / double(reference.pixels.size());
    std::size_t counted = 0, speckled = 0;
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        const double r = luminance(reference.pixels[i]);
        if (r < threshold) continue;
        ++counted;
        if (double(luminance(image.pixels[i])) > kSpeckleRatio * r) ++speckled;
    }
    return counted > 0 ? double(speckled) / double(counted) : 0;
}

}  // namespace

ImageDifference compareImages(const Image& image, const Image& reference, int blockSize,
                              float exposure) {
    if (image.width != reference.width || image.height != reference.height)
        throw std::invalid_argument("images differ in size: " + std::to_string(image.width) + "x" +
                                    std::to_string(image.height) + " and " +
                                    std::to_string(reference.width) + "x" +
                                    std::to_string(reference.height));
    ImageDifference d;
    double rel = 0, sq = 0, sumA = 0, sumR = 0;
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            const double a = image.pixels[i][c], r = reference.pixels[i][c];
            rel += (a - r) * (a - r) / (r * r + kRelativeMseEpsilon);
            sq += (a - r) * (a - r);
            sumA += a;
            sumR += r;
        }
    }
    const double n = 3.0 * double(image.pixels.size());
    d.relativeMse = n > 0 ? rel / n : 0;
    d.rmse = n > 0 ? std::sqrt(sq / n) : 0;
    d.meanRelativeBias = sumR > 0 ? sumA / sumR - 1.0 : 0;

    double blockError = 0;
    int blocks = 0;
    for (int y0 = 0; y0 < image.height; y0 += blockSize) {
        for (int x0 = 0; x0 < image.width; x0 += blockSize) {
            double a = 0, r = 0;
            for (int y = y0; y < std::min(image.height, y0 + blockSize); ++y)
                for (int x = x0; x < std::min(image.width, x0 + blockSize); ++x) {
                    a += meanComponent(image.at(x, y));
                    r += meanComponent(reference.at(x, y));
                }
            if (r <= 1e-6 * blockSize * blockSize) continue;  // black in the reference: no ratio
            blockError += std::fabs(a / r - 1.0);
            ++blocks;
        }
    }
    d.blockRelativeError = blocks > 0 ? blockError / blocks : 0;
    d.ssim = ssim(image, reference, exposure);
    d.speckle = speckle(image, reference);
    return d;
}

}  // namespace igi
