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
    // The variance after this frame, of frames_ + 1 frames (0 while there is one).
    const double inv = 1.0 / (frames_ + 1.0), invDegrees = frames_ > 0 ? 1.0 / frames_ : 0.0;
    for (std::size_t p = std::size_t(rowBegin) * width_; p < std::size_t(rowEnd) * width_; ++p) {
        sumUnfiltered_[3 * p] += unfiltered[p].x;
        sumUnfiltered_[3 * p + 1] += unfiltered[p].y;
        sumUnfiltered_[3 * p + 2] += unfiltered[p].z;
        const double d = double(luminance(filtered[p])) - double(luminance(unfiltered[p]));
        sumDifference2_[p] += d * d;
        // Once per pixel and frame, here where the rows are split among threads: the pooled
        // estimate of meanRows reads each pixel's up to noiseX x noiseY times.
        variance_[p] = frames_ > 0 ? ownVariance(p, inv, invDegrees) : 0.0;
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

double Accumulator::ownVariance(std::size_t p, double inv, double invDegrees) const {
    const double* s = sum_.data() + 3 * p;
    const double* u = sumUnfiltered_.data() + 3 * p;
    const double d = luminance(glm::dvec3(s[0], s[1], s[2]) * inv) -
                     luminance(glm::dvec3(u[0], u[1], u[2]) * inv);
    // The frames' sample variance over their count.
    return std::max(0.0, sumDifference2_[p] * inv - d * d) * invDegrees;
}

std::pair<int, int> Accumulator::meanWindow(int y) const {
    if (!withdrawBlur_ || noiseY_ == 1) return {y, y + 1};
    const int y0 = filterWindowStart(y, noiseY_, height_);
    return {y0, std::min(height_, y0 + noiseY_)};
}

void Accumulator::meanRows(std::vector<glm::vec3>& out, int rowBegin, int rowEnd,
                           int frames) const {
    const double inv = frames > 0 ? 1.0 / double(frames) : 0.0;
    if (!withdrawBlur_ || frames < 2) {
        for (std::size_t p = std::size_t(rowBegin) * width_; p < std::size_t(rowEnd) * width_; ++p)
            out[p] = glm::vec3(
                glm::dvec3(sum_[3 * p] * inv, sum_[3 * p + 1] * inv, sum_[3 * p + 2] * inv));
        return;
    }
    const double tolerance = blurTolerance(frames);
    const bool pooled = noiseX_ * noiseY_ > 1;
    // The window's variances summed down its rows, column by column, then across its columns:
    // three additions a pixel instead of nine (a 3 x 3 window). The order differs from a
    // row-by-row sum only in rounding, which the blend weight is continuous in.
    thread_local std::vector<double> columns;
    columns.resize(std::size_t(width_));
    const int half = (noiseX_ - 1) / 2, windowWidth = std::min(width_, noiseX_);
    for (int y = rowBegin; y < rowEnd; ++y) {
        const int y0 = filterWindowStart(y, noiseY_, height_), y1 = std::min(height_, y0 + noiseY_);
        if (pooled) {
            const double* v = variance_.data() + std::size_t(y0) * width_;
            std::copy_n(v, width_, columns.begin());
            for (int qy = y0 + 1; qy < y1; ++qy) {
                v += width_;
                for (int x = 0; x < width_; ++x) columns[std::size_t(x)] += v[x];
            }
        }
        const double perWindowPixel = 1.0 / double(windowWidth * (y1 - y0));
        for (int x = 0; x < width_; ++x) {
            const std::size_t p = std::size_t(y) * width_ + x;
            const glm::dvec3 filtered(sum_[3 * p] * inv, sum_[3 * p + 1] * inv,
                                      sum_[3 * p + 2] * inv);
            const glm::dvec3 unfiltered(sumUnfiltered_[3 * p] * inv,
                                        sumUnfiltered_[3 * p + 1] * inv,
                                        sumUnfiltered_[3 * p + 2] * inv);
            const double d = luminance(filtered) - luminance(unfiltered);
            double variance = variance_[p];
            if (pooled) {
                // The discontinuity buffer's window: every interleaving cell, also at the
                // borders (shifted inward, never cut).
                const int x0 = std::clamp(x - half, 0, std::max(0, width_ - noiseX_));
                double window = 0.0;
                for (int qx = x0; qx < x0 + windowWidth; ++qx) window += columns[std::size_t(qx)];
                variance = std::max(variance, window * perWindowPixel);
            }
            const double allowed = tolerance * variance;
            const double w = d * d <= allowed ? 1.0 : allowed / (d * d);
            out[p] = glm::vec3(w * filtered + (1.0 - w) * unfiltered);
        }
    }
}

}  // namespace igi
