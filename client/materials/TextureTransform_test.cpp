// The conformance model TextureTransformTest (glTF KHR_texture_transform) loads and renders,
// and its transforms show; a normal map's frame follows its transform.

#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "materials/NormalMap.h"
#include "scene/SceneLoader.h"
#include "testing/TestScenes.h"
#include "util/TestPaths.h"

namespace igi {
namespace {

TEST(TextureTransform, TextureTransformTestLoadsAndRenders) {
    const auto file = igi::testing::sharedScenesDir() / "gltf" / "TextureTransformTest" / "glTF" /
                      "TextureTransformTest.gltf";
    if (!std::filesystem::exists(file)) GTEST_SKIP() << "no " << file;
    Scene scene = loadSceneFile(file);
    int transformed = 0;
    for (const Material& m : scene.materials) transformed += m.diffuseUv.active;
    EXPECT_EQ(transformed, 6);  // offsets U, V, UV, rotation, scale, all
    scene.image = {64, 48, 0};
    testing::InProcessRenderer renderer(scene);
    const Image image = renderer.render(2);
    EXPECT_EQ(renderer.nonFiniteValues(), 0u);
    for (const glm::vec3& p : image.pixels)
        ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
    EXPECT_GT(testing::meanOf(image).x, 0.0);
    Scene plain = scene;
    for (Material& m : plain.materials) m.diffuseUv = UvTransform{};
    testing::InProcessRenderer plainRenderer(plain);
    const Image untransformed = plainRenderer.render(2);
    EXPECT_GT(testing::meanDifference(image, untransformed), 1e-3);
}

TEST(TextureTransform, NormalMapFrameTurnsWithTheTransform) {
    // uv' = R(90 degrees) uv: +u' runs along the old -v, +v' along the old +u.
    normalmap::TangentFrame frame{{1, 0, 0}, {0, 1, 0}};
    const glm::mat2 rotate(0.0f, 1.0f, -1.0f, 0.0f);  // columns: (0, 1), (-1, 0)
    ASSERT_TRUE(normalmap::transformFrame(rotate, frame));
    EXPECT_NEAR(glm::distance(frame.tangent, glm::vec3(0, -1, 0)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::distance(frame.bitangent, glm::vec3(1, 0, 0)), 0.0f, 1e-6f);
    normalmap::TangentFrame scaled{{1, 0, 0}, {0, 1, 0}};
    ASSERT_TRUE(normalmap::transformFrame(glm::mat2(2.0f, 0.0f, 0.0f, -3.0f), scaled));
    EXPECT_EQ(scaled.tangent, glm::vec3(1, 0, 0));
    EXPECT_EQ(scaled.bitangent, glm::vec3(0, -1, 0));  // a mirrored v
    normalmap::TangentFrame singular{{1, 0, 0}, {0, 1, 0}};
    EXPECT_FALSE(normalmap::transformFrame(glm::mat2(1.0f, 1.0f, 1.0f, 1.0f), singular));
}

}  // namespace
}  // namespace igi
