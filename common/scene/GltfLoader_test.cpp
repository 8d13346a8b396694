// glTF: the hand-written triangle.gltf (node transforms, materials, a punctual light).

#include <cmath>

#include <gtest/gtest.h>

#include "scene/SceneLoader.h"
#include "scene/TestScenes.h"

namespace igi {
namespace {

void expectNear(glm::vec3 a, glm::vec3 b, float eps = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

class GltfTriangle : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        scene_ = new Scene(loadSceneFile(test::testdataDir() / "gltf" / "scene.json"));
    }
    static void TearDownTestSuite() { delete scene_; }
    static Scene* scene_;
};
Scene* GltfTriangle::scene_ = nullptr;

TEST_F(GltfTriangle, NodeTransformsAreBakedAndUvsFlipped) {
    ASSERT_EQ(scene_->meshes.size(), 1u);
    const Mesh& m = scene_->meshes[0];
    EXPECT_EQ(m.name, "triangle");
    // Three primitives share one accessor set: 3 x 3 vertices, translated by the node.
    ASSERT_EQ(m.triangles.size(), 3u);
    ASSERT_EQ(m.positions.size(), 9u);
    expectNear(m.positions[m.triangles[0].y], {1, 0, -2});
    expectNear(m.normals[m.triangles[0].y], {0, 0, 1});
    // glTF's v = 0 is the top of the image, igi's the bottom.
    EXPECT_EQ(m.uvs[m.triangles[0].x], glm::vec2(0, 1));
    EXPECT_EQ(m.uvs[m.triangles[0].z], glm::vec2(0, 0));
    EXPECT_EQ(m.materialIds, (std::vector<std::uint32_t>{0, 1, 2}));
}

TEST_F(GltfTriangle, Materials) {
    const auto& mats = scene_->materials;
    ASSERT_EQ(mats.size(), 3u);
    EXPECT_EQ(mats[0].name, "chrome");
    EXPECT_EQ(mats[0].reflection, Reflection::Mirror);
    expectNear(mats[0].specular, {0.9f, 0.8f, 0.7f});
    EXPECT_EQ(mats[1].name, "water");
    EXPECT_TRUE(mats[1].glass);
    EXPECT_FLOAT_EQ(mats[1].ior, 1.33f);
    EXPECT_EQ(mats[2].name, "glow");
    expectNear(mats[2].emission, {4, 2, 1});  // emissiveFactor x emissiveStrength
    expectNear(mats[2].diffuse, {0.2f, 0.3f, 0.4f});
    EXPECT_EQ(mats[2].reflection, Reflection::None);
}

TEST_F(GltfTriangle, PunctualLightPlacedByNodesAndMeshTransform) {
    ASSERT_EQ(scene_->pointLights.size(), 1u);
    const PointLight& l = scene_->pointLights[0];
    EXPECT_EQ(l.name, "lamp");
    // Node (0,3,0) under a node scaled by 2, then the scene file's translate (10,0,0).
    expectNear(l.position, {10, 6, 0});
    // color x intensity / (4 pi), intensity = 40 pi.
    expectNear(l.intensity, {10, 5, 2.5f}, 1e-4f);
}

TEST(GltfLoader, MissingImageNamesIt) {
    const std::string gltf = R"({"asset": {"version": "2.0"},
        "images": [{"uri": "gone.png"}], "textures": [{"source": 0}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]})";
    const std::string what = test::sceneErrorOf([&] {
        test::parseInline(
            R"({"meshes": [{"file": "a/m.gltf"}], "camera": {"position": [0, 0, 1], "look_at": [0, 0, 0]}})",
            {{"a/m.gltf", gltf}});
    });
    EXPECT_NE(what.find("a/m.gltf: /images/0: image 'gone.png' not found or unreadable"),
              std::string::npos)
        << what;
}

TEST(GltfLoader, InvalidJsonIsAnErrorNamingTheFile) {
    const std::string what = test::sceneErrorOf([] {
        test::parseInline(R"({"meshes": [{"file": "m.gltf"}]})", {{"m.gltf", "{ not json"}});
    });
    EXPECT_NE(what.find("m.gltf: cannot load glTF"), std::string::npos) << what;
}

}  // namespace
}  // namespace igi
