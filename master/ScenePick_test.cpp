#include "ScenePick.h"

#include <gtest/gtest.h>

namespace igi {
namespace {

Mesh square(const std::string& name, float z) {
    Mesh m;
    m.name = name;
    m.positions = {{-1, -1, z}, {1, -1, z}, {1, 1, z}, {-1, 1, z}};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    m.materialIds = {0, 0};
    return m;
}

// A camera at z = 5 looking down -z at a far wall (z = -2, 4 x 4) and a near square (z = 0,
// 0.5 x 0.5) that can be moved.
Scene scene() {
    Scene s;
    s.image.width = 200;
    s.image.height = 100;
    s.camera.position = {0, 0, 5};
    s.camera.lookAt = {0, 0, 0};
    s.camera.fovYDeg = 60;
    s.meshes = {square("wall", -0.5f), square("near", 0)};  // the scale takes the wall to z = -2
    s.meshes[0].transform.scale = glm::vec3(4);
    s.meshes[1].transform.scale = glm::vec3(0.5f);
    return s;
}

TEST(ScenePick, FindsTheNearestSurfaceUnderThePixel) {
    const Scene s = scene();
    const SceneState state = SceneState::of(s);
    const auto center = pickObject(s, state, 100, 50);
    ASSERT_TRUE(center);
    EXPECT_EQ(center->mesh, 1u);
    EXPECT_NEAR(center->distance, 5.0f, 1e-4f);
    EXPECT_NEAR(center->point.z, 0.0f, 1e-4f);
    // Off the small square, the wall; off the wall (the image's corner), nothing.
    const auto side = pickObject(s, state, 130, 50);
    ASSERT_TRUE(side);
    EXPECT_EQ(side->mesh, 0u);
    EXPECT_NEAR(side->point.z, -2.0f, 1e-4f);
    EXPECT_FALSE(pickObject(s, state, 0, 0));
}

TEST(ScenePick, SeesTheMeshesWhereTheStatePutsThem) {
    const Scene s = scene();
    SceneState state = SceneState::of(s);
    state.transforms[1].translate = {1.6f, 0, 0};  // off the center, into the ray at x = 130
    const auto center = pickObject(s, state, 100, 50);
    ASSERT_TRUE(center);
    EXPECT_EQ(center->mesh, 0u);
    const auto side = pickObject(s, state, 130, 50);
    ASSERT_TRUE(side);
    EXPECT_EQ(side->mesh, 1u);
}

// An instance of a glTF file's shared primitive (a part of the file's object, placed by its node
// matrix after the object's transform) is picked where it stands, as its object: what the pick
// names is what `igi-ctl object` moves.
TEST(ScenePick, AnInstancePicksItsObject) {
    Scene s = scene();
    Mesh part;
    part.name = "wall";
    part.geometryOf = 1;  // the near square's triangles
    part.partOf = 0;      // a part of the wall's object
    part.instanced = true;
    part.local = glm::mat4(1.0f);
    part.local[3] = glm::vec4(0.4f, 0, 0.5f, 1);  // in the wall's space (scaled by 4)
    s.meshes[1].instanced = true;
    s.meshes.push_back(part);
    SceneState state = SceneState::of(s);
    // At the wall's scale, the part covers x in [-2.4, 5.6] at z = 2: the ray at x = 130 meets it.
    const auto side = pickObject(s, state, 130, 50);
    ASSERT_TRUE(side);
    EXPECT_EQ(side->mesh, 0u);
    EXPECT_NEAR(side->point.z, 2.0f, 1e-4f);
    // Moved with its object.
    state.transforms[0].translate = {0, 0, -1};
    const auto moved = pickObject(s, state, 130, 50);
    ASSERT_TRUE(moved);
    EXPECT_EQ(moved->mesh, 0u);
    EXPECT_NEAR(moved->point.z, 1.0f, 1e-4f);
}

}  // namespace
}  // namespace igi
