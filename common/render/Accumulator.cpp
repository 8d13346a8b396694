#include "render/Accumulator.h"

#include <algorithm>
#include <cmath>

#include "math/Color.h"
#include "render/DiscontinuityFilter.h"

namespace igi {

void Accumulator::reset(int width, int height, bool withdrawBlur, int noiseX, int noiseY) {
    width_ = width;
    height_ = height;
    frames_ = 0;
    withdrawBlur_ = withdrawBlur;
    noiseX_ = std::max(1, noiseX);
    noiseY_ = std::max(1, noiseY);
    const std::size_t pixels = std::size_t(width) * height;
    sum_.assign(pixels * 3, 0.0);
    sumUnfiltered_.assign(withdrawBlur ? pixels * 3 : 0, 0.0);
    sumDifference2_.assign(withdrawBlur ? pixels : 0, 0.0);
    variance_.assign(withdrawBlur ? pixels : 0, 0.0);
}

void Accumulator::addRows(const std::vector<glm::vec3>& frame, int rowBegin, int rowEnd) {
    for (std::size_t p = std::size_t(rowBegin) * width_; p < std::size_t(rowEnd) * width_; ++p) {
        sum_[3 * p] += frame[p].x;
        sum_[3 * p + 1] += frame[p].y;
        sum_[3 * p + 2] += frame[p].z;
    }
}

void Accumulator::addRows(const std::vector<glm::vec3>& filtered,
                          const std::vector<glm::vec3>& unfiltered, int rowBegin, int rowEnd) {
    addRows(filtered, rowBegin, rowEnd);
    if (!withdrawBlur_) return;
    for (std::size_t p = std::size_t(rowBegin) * width_; p < std::size_t(rowEnd) * width_; ++p) {
        sumUnfiltered_[3 * p] += unfiltered[p].x;
        sumUnfiltered_[3 * p + 1] += unfiltered[p].y;
        sumUnfiltered_[3 * p + 2] += unfiltered[p].z;
        const double d = double(luminance(filtered[p])) - double(luminance(unfiltered[p]));
        sumDifference2_[p] += d * d;
        // Once per pixel and frame, here where the rows are split among threads: the pooled
        // estimate of meanRows reads each pixel's up to noiseX x noiseY times.
        variance_[p] = ownVariance(p, frames_ + 1);
    }
}

double Accumulator::blurTolerance(int frames) {
    // t_{0.975}(nu) for nu = 1 .. 30 degrees of freedom.
    static constexpr double kT[] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306,
                                    2.262,  2.228, 2.201, 2.179, 2.160, 2.145, 2.131, 2.120,
                                    2.110,  2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064,
                                    2.060,  2.056, 2.052, 2.048, 2.045, 2.042};
    const int nu = std::max(1, frames - 1);
    // Beyond the table, the first terms of the Cornish-Fisher expansion around z = 1.96.
    constexpr double z = 1.959964;
    const double g1 = (z * z * z + z) / 4.0;
    const double g2 = (5.0 * std::pow(z, 5) + 16.0 * z * z * z + 3.0 * z) / 96.0;
    const double t = nu <= 30 ? kT[nu - 1] : z + g1 / nu + g2 / (double(nu) * nu);
    return t * t;
}

double Accumulator::ownVariance(std::size_t p, int frames) const {
    if (frames < 2) return 0.0;
    const double inv = 1.0 / frames;
    const double d = luminance(glm::dvec3(sum_[3 * p], sum_[3 * p + 1], sum_[3 * p + 2]) * inv) -
                     luminance(glm::dvec3(sumUnfiltered_[3 * p], sumUnfiltered_[3 * p + 1],
                                          sumUnfiltered_[3 * p + 2]) *
                               inv);
    // The frames' sample variance over their count.
    return std::max(0.0, sumDifference2_[p] * inv - d * d) / (frames - 1.0);
}

double Accumulator::windowVariance(int x, int y) const {
    // The discontinuity buffer's window: every interleaving cell, also at the borders.
    const int x0 = filterWindowStart(x, noiseX_, width_),
              y0 = filterWindowStart(y, noiseY_, height_);
    const int x1 = std::min(width_, x0 + noiseX_), y1 = std::min(height_, y0 + noiseY_);
    double sum = 0.0;
    for (int qy = y0; qy < y1; ++qy)
        for (int qx = x0; qx < x1; ++qx) sum += variance_[std::size_t(qy) * width_ + qx];
    return sum / double((x1 - x0) * (y1 - y0));
}

void Accumulator::meanRows(std::vector<glm::vec3>& out, int rowBegin, int rowEnd) const {
    const double n = frames_;
    const double tolerance = blurTolerance(frames_);
    const double inv = frames_ > 0 ? 1.0 / n : 0.0;
    for (std::size_t p = std::size_t(rowBegin) * width_; p < std::size_t(rowEnd) * width_; ++p) {
        const glm::dvec3 filtered(sum_[3 * p] * inv, sum_[3 * p + 1] * inv, sum_[3 * p + 2] * inv);
        if (!withdrawBlur_ || frames_ < 2) {
            out[p] = glm::vec3(filtered);
            continue;
        }
        const glm::dvec3 unfiltered(sumUnfiltered_[3 * p] * inv, sumUnfiltered_[3 * p + 1] * inv,
                                    sumUnfiltered_[3 * p + 2] * inv);
        const double d = luminance(filtered) - luminance(unfiltered);
        double variance = variance_[p];
        if (noiseX_ * noiseY_ > 1) {
            const int x = int(p % std::size_t(width_)), y = int(p / std::size_t(width_));
            variance = std::max(variance, windowVariance(x, y));
        }
        const double allowed = tolerance * variance;
        const double w = d * d <= allowed ? 1.0 : allowed / (d * d);
        out[p] = glm::vec3(w * filtered + (1.0 - w) * unfiltered);
    }
}

}  // namespace igi
