#include "integrators/PixelSampler.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <set>
#include <utility>

#include <gtest/gtest.h>

#include "render/RowAccumulator.h"

namespace igi {
namespace {

constexpr std::uint64_t kSeed = 11;

// A pixel's positions over the frames are one stratified sequence: the first 2^m frames put
// one point in every elementary interval of area 2^-m of the pixel.
TEST(PixelSampler, FramesStratifyThePixel) {
    for (std::uint32_t pixel : {0u, 77u, 4096u})
        for (int m = 1; m <= 8; ++m)
            for (int k = 0; k <= m; ++k) {  // intervals 2^-k wide, 2^-(m-k) high
                std::set<std::pair<int, int>> cells;
                for (std::uint32_t frame = 0; frame < (1u << m); ++frame) {
                    const PixelSampler s(kSeed, SampleStream::EyePath, pixel, frame);
                    cells.emplace(int(s.get(0) * float(1 << k)),
                                  int(s.get(1) * float(1 << (m - k))));
                }
                EXPECT_EQ(cells.size(), std::size_t(1) << m) << "pixel " << pixel << ", 2^" << m;
            }
}

// A pixel cut by a straight edge: 1 on one side, 0 on the other. Its footprint's noise is all
// there is, and stratified positions make it converge faster than 1/n.
struct EdgePixel {
    double nx, ny, c;  // inside where nx (x - 1/2) + ny (y - 1/2) < c

    bool inside(double x, double y) const { return nx * (x - 0.5) + ny * (y - 0.5) < c; }

    // The inside's area: the unit square clipped by the half-plane (Sutherland-Hodgman), then
    // the shoelace formula.
    double area() const {
        const std::array<std::pair<double, double>, 4> square{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
        std::vector<std::pair<double, double>> out;
        auto f = [&](const std::pair<double, double>& p) {
            return nx * (p.first - 0.5) + ny * (p.second - 0.5) - c;
        };
        for (std::size_t i = 0; i < square.size(); ++i) {
            const auto& a = square[i];
            const auto& b = square[(i + 1) % square.size()];
            const double fa = f(a), fb = f(b);
            if (fa < 0) out.push_back(a);
            if ((fa < 0) != (fb < 0)) {
                const double t = fa / (fa - fb);
                out.emplace_back(a.first + t * (b.first - a.first),
                                 a.second + t * (b.second - a.second));
            }
        }
        double twice = 0;
        for (std::size_t i = 0; i < out.size(); ++i) {
            const auto& a = out[i];
            const auto& b = out[(i + 1) % out.size()];
            twice += a.first * b.second - b.first * a.second;
        }
        return std::abs(twice) / 2;
    }
};

// Over many edge pixels, after n frames: the mean of the half-means' estimate
// (A - B)^2 nA nB / n^2 against the mean of the true squared error, for n = 8, 16, ..., 256.
// `position(pixel, frame)` gives the frame's position in the pixel, `first(frame)` the halves.
std::vector<double> estimateOverTruth(
    const std::function<std::pair<float, float>(std::uint32_t, std::uint32_t)>& position,
    const std::function<bool(int)>& first) {
    constexpr std::uint32_t kPixels = 20000;
    constexpr int kFrames = 256;
    SplitMix64 random(5);
    std::vector<double> estimate(6, 0.0), truth(6, 0.0);
    for (std::uint32_t p = 0; p < kPixels; ++p) {
        const double angle = 6.283185307179586 * Sobol::toFloat(std::uint32_t(random.next()));
        const EdgePixel edge{std::cos(angle), std::sin(angle),
                             1.4 * Sobol::toFloat(std::uint32_t(random.next())) - 0.7};
        const double exact = edge.area();
        double sum = 0, sumA = 0;
        int nA = 0;
        for (int frame = 0, k = 0; frame < kFrames; ++frame) {
            const auto [x, y] = position(p, std::uint32_t(frame));
            const double v = edge.inside(x, y) ? 1.0 : 0.0;
            sum += v;
            if (first(frame)) {
                sumA += v;
                ++nA;
            }
            const int n = frame + 1, nB = n - nA;
            if (n < 8 || (n & (n - 1)) != 0) continue;
            const double mean = sum / n, a = sumA / nA, b = (sum - sumA) / nB;
            truth[std::size_t(k)] += (mean - exact) * (mean - exact);
            estimate[std::size_t(k)] += (a - b) * (a - b) * nA * nB / (double(n) * n);
            ++k;
        }
    }
    std::vector<double> ratio;
    for (std::size_t k = 0; k < truth.size(); ++k) ratio.push_back(estimate[k] / truth[k]);
    return ratio;
}

// Why the rays that gather the light at its edges (IgiIntegrator::gatherLightAtEdges) are
// independent from frame to frame: with the eye ray's position, one sequence over the frames,
// the error estimate's halves (RowAccumulator::inFirstHalf) differ more than the mean errs at
// a pixel cut by an edge (docs/ERROR_ESTIMATE.md); with positions drawn afresh in each frame,
// as gatherLightAtEdges's are, they do not.
TEST(PixelSampler, HalvesOfOneSequenceOverestimateAnEdgesError) {
    const auto sequence = estimateOverTruth(
        [](std::uint32_t pixel, std::uint32_t frame) {
            const PixelSampler s(kSeed, SampleStream::EyePath, pixel, frame);
            return std::make_pair(s.get(0), s.get(1));
        },
        RowAccumulator::inFirstHalf);
    const auto fresh = estimateOverTruth(
        [](std::uint32_t pixel, std::uint32_t frame) {
            const std::uint64_t h = hashValues(kSeed, pixel, frame);
            return std::make_pair(Sobol::scrambled(0, 0, std::uint32_t(h)),
                                  Sobol::scrambled(0, 1, std::uint32_t(h >> 32)));
        },
        RowAccumulator::inFirstHalf);
    for (std::size_t k = 0; k < sequence.size(); ++k) {
        const int n = 8 << k;
        std::printf("%d frames: estimate / true squared error %.3f (one sequence), %.3f (fresh)\n",
                    n, sequence[k], fresh[k]);
        if (n >= 16) {
            EXPECT_GT(sequence[k], 1.5) << n << " frames";
        }
        // The halves are blocks of 2^j frames, each stratified as the whole is
        // (RowAccumulator::inFirstHalf): the excess stays under 4x (2.4x to 3.9x). With one
        // frame of each pair in each half, at random, this test printed 2x to 19x from 16
        // frames on.
        EXPECT_LT(sequence[k], 4.2) << n << " frames";
        EXPECT_GT(fresh[k], 0.9) << n << " frames";
        EXPECT_LT(fresh[k], 1.1) << n << " frames";
    }
}

}  // namespace
}  // namespace igi
