#include "scene/Transform.h"

#include <gtest/gtest.h>

namespace igi {
namespace {

glm::vec3 apply(const Transform& t, glm::vec3 p) {
    return glm::vec3(t.matrix() * glm::vec4(p, 1.0f));
}

void expectNear(glm::vec3 a, glm::vec3 b) {
    EXPECT_NEAR(a.x, b.x, 1e-5f);
    EXPECT_NEAR(a.y, b.y, 1e-5f);
    EXPECT_NEAR(a.z, b.z, 1e-5f);
}

TEST(Transform, ScalesThenRotatesThenTranslates) {
    Transform t;
    t.scale = glm::vec3(2.0f, 3.0f, 4.0f);
    t.rotateDeg = glm::vec3(0.0f, 0.0f, 90.0f);
    t.translate = glm::vec3(0.0f, 0.0f, 5.0f);
    // (1,0,0) -> scale (2,0,0) -> Rz90 (0,2,0) -> +(0,0,5).
    expectNear(apply(t, {1, 0, 0}), {0, 2, 5});
    // Scale applies before the rotation: the y extent (3) ends up along -x.
    expectNear(apply(t, {0, 1, 0}), {-3, 0, 5});
}

TEST(Transform, RotatesAboutXThenYThenZ) {
    Transform t;
    t.rotateDeg = glm::vec3(90.0f, 90.0f, 0.0f);
    // Rx90: (0,1,0) -> (0,0,1); then Ry90: (0,0,1) -> (1,0,0). Y first would give (0,0,1).
    expectNear(apply(t, {0, 1, 0}), {1, 0, 0});
    Transform u;
    u.rotateDeg = glm::vec3(0.0f, 90.0f, 90.0f);
    // Ry90: (1,0,0) -> (0,0,-1); Rz90 leaves it. Z first would give (0,1,0).
    expectNear(apply(u, {1, 0, 0}), {0, 0, -1});
}

TEST(Transform, DefaultIsIdentity) {
    expectNear(apply(Transform{}, {1, 2, 3}), {1, 2, 3});
}

}  // namespace
}  // namespace igi
