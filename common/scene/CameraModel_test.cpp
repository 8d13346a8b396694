#include "scene/CameraModel.h"

#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace igi {
namespace {

// The eye rays of a chunk are computed four at a time (directions); each must have the bits
// of the one-at-a-time direction, or an image would depend on how its pixels were grouped.
TEST(CameraModel, DirectionsFourAtATimeHaveTheBitsOfOneAtATime) {
    Camera camera;
    camera.position = {0.3f, 1.1f, 4.7f};
    camera.lookAt = {-0.2f, 0.4f, 0.1f};
    camera.up = {0.1f, 1.0f, 0.05f};
    camera.fovYDeg = 51.0f;
    const CameraModel model(camera, 641, 479);
    std::mt19937 random(3);
    std::uniform_real_distribution<float> x(-2.0f, 643.0f), y(-2.0f, 481.0f);
    for (const int n : {1, 3, 4, 7, 64, 65}) {  // whole groups of four and tails
        std::vector<float> px(static_cast<std::size_t>(n)), py(static_cast<std::size_t>(n));
        for (int i = 0; i < n; ++i) px[std::size_t(i)] = x(random), py[std::size_t(i)] = y(random);
        std::vector<glm::vec3> out(static_cast<std::size_t>(n));
        model.directions(px.data(), py.data(), n, out.data());
        for (int i = 0; i < n; ++i) {
            const glm::vec3 one = model.direction(px[std::size_t(i)], py[std::size_t(i)]);
            EXPECT_EQ(std::memcmp(&one, &out[std::size_t(i)], sizeof one), 0)
                << "pixel " << i << " of " << n;
        }
    }
}

}  // namespace
}  // namespace igi

namespace igi {
namespace {

// pixelOf inverts direction(): a point along the ray through (px, py) projects back there,
// near or far, with any camera (to float precision: the camera's position is subtracted).
TEST(CameraModel, PixelOfInvertsDirection) {
    const Camera cameras[] = {{}, {{3, -2, 5}, {0.5f, 1, -4}, {0, 0, 1}, 70.0f}};
    for (const Camera& c : cameras) {
        const CameraModel camera(c, 320, 200);
        for (const float px : {0.0f, 13.25f, 160.0f, 319.5f})
            for (const float py : {0.0f, 99.75f, 199.0f})
                for (const float t : {0.5f, 1.0f, 1e3f}) {
                    const glm::vec3 p = camera.origin() + t * camera.direction(px, py);
                    EXPECT_GT(camera.depth(p), 0.0f);
                    const glm::vec2 back = camera.pixelOf(p);
                    EXPECT_NEAR(back.x, px, 2e-3f) << t;
                    EXPECT_NEAR(back.y, py, 2e-3f) << t;
                }
        EXPECT_LT(camera.depth(camera.origin() - camera.direction(160, 100)), 0.0f);
    }
}

}  // namespace
}  // namespace igi
