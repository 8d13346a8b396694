#include "render/Accumulator.h"

#include <gtest/gtest.h>

namespace igi {
namespace {

TEST(Accumulator, MeanOfFramesAndReset) {
    Accumulator a;
    a.reset(2, 2);
    for (float v : {1.0f, 2.0f, 6.0f}) {
        a.addRows(std::vector<glm::vec3>(4, glm::vec3(v, 2 * v, 0)), 0, 2);
        a.endFrame();
    }
    std::vector<glm::vec3> mean(4);
    a.meanRows(mean, 0, 2);
    EXPECT_EQ(a.frames(), 3);
    EXPECT_FLOAT_EQ(mean[3].x, 3.0f);
    EXPECT_FLOAT_EQ(mean[3].y, 6.0f);
    a.reset(2, 2);
    a.addRows(std::vector<glm::vec3>(4, glm::vec3(5)), 0, 2);
    a.endFrame();
    a.meanRows(mean, 0, 2);
    EXPECT_FLOAT_EQ(mean[0].x, 5.0f);
}

TEST(Accumulator, ManyFramesLoseNoPrecision) {
    Accumulator a;
    a.reset(1, 1);
    std::vector<glm::vec3> frame(1);
    for (int i = 0; i < 100000; ++i) {
        frame[0] = glm::vec3(i % 2 ? 1e-3f : 1e3f);
        a.addRows(frame, 0, 1);
        a.endFrame();
    }
    std::vector<glm::vec3> mean(1);
    a.meanRows(mean, 0, 1);
    EXPECT_NEAR(mean[0].x, 500.0005f, 1e-3f);
}

// Two frames whose unfiltered values differ from the filtered ones by +1 and +0.6: one
// difference is all the variance estimate has, so the test must not believe a bias yet (the
// old two-sigma rule did, and showed the noisy unfiltered mean in half the image).
TEST(Accumulator, TwoFramesKeepTheFilteredMeanUnlessTheDifferenceIsOverwhelming) {
    Accumulator a;
    a.reset(1, 1, /*withdrawBlur=*/true);
    for (float u : {2.0f, 1.6f}) {
        a.addRows(std::vector<glm::vec3>(1, glm::vec3(1.0f)),
                  std::vector<glm::vec3>(1, glm::vec3(u)), 0, 1);
        a.endFrame();
    }
    std::vector<glm::vec3> mean(1);
    a.meanRows(mean, 0, 1);
    EXPECT_FLOAT_EQ(mean[0].x, 1.0f);
}

// A filter that is biased at a pixel (filtered 1, unfiltered 0.5 with noise of +-0.2): as frames
// come in the difference becomes significant and the mean moves to the unfiltered one.
TEST(Accumulator, ABiasedFilterIsWithdrawnAsFramesComeIn) {
    Accumulator a;
    a.reset(1, 1, /*withdrawBlur=*/true);
    std::vector<glm::vec3> mean(1);
    for (int i = 0; i < 64; ++i) {
        const float u = 0.5f + (i % 2 ? 0.2f : -0.2f);
        a.addRows(std::vector<glm::vec3>(1, glm::vec3(1.0f)),
                  std::vector<glm::vec3>(1, glm::vec3(u)), 0, 1);
        a.endFrame();
        if (i == 1) {
            a.meanRows(mean, 0, 1);
            EXPECT_GT(mean[0].x, 0.5f) << "two frames already lean to the unfiltered mean";
        }
    }
    a.meanRows(mean, 0, 1);
    EXPECT_NEAR(mean[0].x, 0.5f, 0.01f);
}

// Noise alone never withdraws the blur for long: unfiltered = filtered +- 1, alternating.
TEST(Accumulator, NoiseAloneKeepsTheFilteredMean) {
    Accumulator a;
    a.reset(1, 1, /*withdrawBlur=*/true);
    for (int i = 0; i < 64; ++i) {
        a.addRows(std::vector<glm::vec3>(1, glm::vec3(1.0f)),
                  std::vector<glm::vec3>(1, glm::vec3(i % 2 ? 2.0f : 0.0f)), 0, 1);
        a.endFrame();
    }
    std::vector<glm::vec3> mean(1);
    a.meanRows(mean, 0, 1);
    EXPECT_FLOAT_EQ(mean[0].x, 1.0f);
}

TEST(Accumulator, BlurToleranceIsStudentsTFallingToTwoSigma) {
    EXPECT_NEAR(Accumulator::blurTolerance(2), 12.706 * 12.706, 1e-6);
    EXPECT_NEAR(Accumulator::blurTolerance(11), 2.228 * 2.228, 1e-6);
    for (int n = 2; n < 1000; ++n)
        EXPECT_LT(Accumulator::blurTolerance(n + 1), Accumulator::blurTolerance(n)) << n;
    EXPECT_NEAR(Accumulator::blurTolerance(31), 2.042 * 2.042, 0.01);     // table's last entry
    EXPECT_NEAR(Accumulator::blurTolerance(32), 2.0395 * 2.0395, 0.002);  // the expansion's first
    EXPECT_NEAR(Accumulator::blurTolerance(100000), 1.96 * 1.96, 0.01);
}

// Heavy-tailed noise: four pixels of one window share a filtered mean of 1; three of them have
// drawn rare large terms (unfiltered 0 or 4), the fourth has not (unfiltered 0.8, steady). Judged
// alone, the fourth pixel's difference looks significant and its blur is withdrawn (a dark
// dot); with the variance pooled over the window, its neighbours' noise keeps the filter.
TEST(Accumulator, PooledNoiseKeepsTheBlurWhereOnlyNeighboursDrewSpikes) {
    auto run = [](int noiseX) {
        Accumulator a;
        a.reset(4, 1, /*withdrawBlur=*/true, noiseX, 1);
        for (int i = 0; i < 32; ++i) {
            const float spike = i % 4 == 0 ? 4.0f : 0.0f;
            const std::vector<glm::vec3> filtered(4, glm::vec3(1.0f));
            const std::vector<glm::vec3> unfiltered{glm::vec3(0.8f), glm::vec3(spike),
                                                    glm::vec3(spike), glm::vec3(spike)};
            a.addRows(filtered, unfiltered, 0, 1);
            a.endFrame();
        }
        std::vector<glm::vec3> mean(4);
        a.meanRows(mean, 0, 1);
        return mean[0].x;
    };
    EXPECT_LT(run(1), 0.85f) << "alone, the steady pixel's blur is withdrawn";
    EXPECT_FLOAT_EQ(run(4), 1.0f) << "pooled, its neighbours' spikes show the noise";
}

}  // namespace
}  // namespace igi
