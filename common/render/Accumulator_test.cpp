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

}  // namespace
}  // namespace igi
