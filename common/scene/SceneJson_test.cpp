// Good scene files: every key lands in the right field.

#include <cmath>

#include <gtest/gtest.h>

#include "scene/SceneBounds.h"
#include "scene/SceneLoader.h"
#include "scene/TestScenes.h"

namespace igi {
namespace {

void expectNear(glm::vec3 a, glm::vec3 b, float eps = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

class MinimalScene : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        scene_ = new Scene(loadSceneFile(test::testdataDir() / "minimal" / "scene.json"));
    }
    static void TearDownTestSuite() { delete scene_; }
    static Scene* scene_;
};
Scene* MinimalScene::scene_ = nullptr;

TEST_F(MinimalScene, ImageAndCamera) {
    const Scene& s = *scene_;
    EXPECT_EQ(s.image.width, 320);
    EXPECT_EQ(s.image.height, 240);
    EXPECT_FLOAT_EQ(s.image.exposure, 0.5f);
    expectNear(s.camera.position, {0.5f, 0.5f, 3.0f});
    expectNear(s.camera.lookAt, {0.5f, 0.5f, 0.0f});
    expectNear(s.camera.up, {0, 1, 0});
    EXPECT_FLOAT_EQ(s.camera.fovYDeg, 50.0f);
}

TEST_F(MinimalScene, MeshesNamesAndTransforms) {
    const Scene& s = *scene_;
    ASSERT_EQ(s.meshes.size(), 2u);
    EXPECT_EQ(s.meshes[0].name, "room");
    EXPECT_EQ(s.meshes[1].name, "box");  // the file's stem
    EXPECT_EQ(s.meshes[0].file, "box.obj");
    expectNear(s.meshes[0].transform.translate, {1, 2, 3});
    expectNear(s.meshes[0].transform.rotateDeg, {0, 90, 0});
    expectNear(s.meshes[0].transform.scale, {2, 2, 2});
    EXPECT_EQ(s.meshes[1].transform, Transform{});
}

TEST_F(MinimalScene, ObjIsDeIndexedWithFlatFacesWhereNormalsAreMissing) {
    const Mesh& m = scene_->meshes[0];
    // The quad shares its 4 (v, vt, vn) corners; the normal-less triangle gets 3 of its own.
    ASSERT_EQ(m.triangles.size(), 3u);
    ASSERT_EQ(m.positions.size(), 7u);
    ASSERT_EQ(m.normals.size(), 7u);
    ASSERT_EQ(m.uvs.size(), 7u);
    for (int c = 0; c < 2; ++c) {
        for (int k = 0; k < 3; ++k) expectNear(m.normals[m.triangles[c][k]], {0, 1, 0});
    }
    // Triangle 5 6 7: (0,1,0), (1,1,0), (0.5,1,1): normal cross((1,0,0), (0.5,0,1)) = (0,-1,0).
    for (int k = 0; k < 3; ++k) expectNear(m.normals[m.triangles[2][k]], {0, -1, 0});
    // The floor's corner 3 (1,0,1) carries vt 3 (1,1).
    for (int k = 0; k < 3; ++k) {
        const glm::uvec3 t = m.triangles[0];
        if (m.positions[t[k]] == glm::vec3(1, 0, 1)) {
            EXPECT_EQ(m.uvs[t[k]], glm::vec2(1, 1));
        }
    }
}

TEST_F(MinimalScene, MaterialsAppendedPerFileAndOverridden) {
    const Scene& s = *scene_;
    // box.obj is named twice: loaded once, the second entry an instance of the first (its
    // triangles and materials; docs/SCENE_FORMAT.md, "Instances").
    ASSERT_EQ(s.materials.size(), 2u);
    EXPECT_EQ(s.meshes[0].materialIds, (std::vector<std::uint32_t>{0, 0, 1}));
    EXPECT_EQ(s.meshes[1].geometryOf, 0);
    EXPECT_TRUE(s.meshes[1].materialIds.empty());
    for (std::uint32_t t = 0; t < 3; ++t) EXPECT_EQ(materialOf(s, 1, t), materialOf(s, 0, t));
    for (int i : {0}) {
        const Material& floor = s.materials[i];
        EXPECT_EQ(floor.name, "floor");
        EXPECT_EQ(floor.reflection, Reflection::Glossy);  // the override
        expectNear(floor.specular, {0.2f, 0.3f, 0.4f});
        EXPECT_FLOAT_EQ(floor.phongExponent, 20.0f);
        expectNear(floor.diffuse, {0.5f, 0.5f, 0.5f});  // from the MTL, 0.5 + 0.4 <= 1
        EXPECT_EQ(floor.diffuseTexture, 0);
    }
    EXPECT_TRUE(s.materials[1].isEmissive());
    expectNear(s.materials[1].emission, {4, 4, 4});
    // One texture, decoded once for both files.
    ASSERT_EQ(s.textures.size(), 1u);
    EXPECT_EQ(s.textures[0].width, 2);
}

TEST_F(MinimalScene, LightsAndHeadlight) {
    const Scene& s = *scene_;
    ASSERT_EQ(s.punctualLights.size(), 2u);
    EXPECT_EQ(s.punctualLights[0].name, "bulb");
    expectNear(s.punctualLights[0].position, {0, 2, 0});
    expectNear(s.punctualLights[0].intensity, {1, 2, 3});
    ASSERT_EQ(s.quadLights.size(), 1u);
    EXPECT_EQ(s.quadLights[0].name, "light1");
    expectNear(s.quadLights[0].corner, {0, 1.9f, 0});
    expectNear(s.quadLights[0].edge1, {1, 0, 0});
    expectNear(s.quadLights[0].edge2, {0, 0, 1});
    expectNear(s.quadLights[0].radiance, {5, 5, 5});
    // The headlight: at the camera, irradiance 1 at the look-at point 3 units away.
    EXPECT_EQ(s.punctualLights[1].name, "headlight");
    expectNear(s.punctualLights[1].position, s.camera.position);
    expectNear(s.punctualLights[1].intensity, {9, 9, 9}, 1e-4f);
}

TEST_F(MinimalScene, RenderSettings) {
    const RenderSettings& r = scene_->render;
    EXPECT_EQ(r.integrator, IntegratorKind::Path);
    EXPECT_EQ(r.interleaveX, 4);
    EXPECT_EQ(r.interleaveY, 2);
    EXPECT_EQ(r.directSamples, 8);
    EXPECT_EQ(r.vplPaths, 100);
    EXPECT_EQ(r.indirectVpls, 30);
    EXPECT_EQ(r.maxLightPathLength, 5);
    EXPECT_FLOAT_EQ(r.clampDistance, 0.05f);
    EXPECT_EQ(r.causticPhotons, 1000);
    EXPECT_FLOAT_EQ(r.causticRadius, 0.02f);
    EXPECT_EQ(r.maxEyeDepth, 6);
    EXPECT_EQ(r.filterX, 5);
    EXPECT_EQ(r.filterY, 3);
    EXPECT_FLOAT_EQ(r.filterDepthThreshold, 0.1f);
    EXPECT_FLOAT_EQ(r.filterNormalThreshold, 0.8f);
    EXPECT_FALSE(r.accumulate);
    EXPECT_EQ(r.pathSamples, 64);
    EXPECT_EQ(r.maxPathLength, 12);
    EXPECT_EQ(r.tileSize, 16);
    EXPECT_EQ(r.seed, 12345678901ull);
}

TEST(SceneJson, DefaultsWhenSectionsAreAbsent) {
    const Scene s = test::parseInline(
        R"({"lights": [{"type": "point", "position": [0, 0, 0], "intensity": 1}]})");
    EXPECT_EQ(s.image.width, 640);
    EXPECT_EQ(s.image.height, 480);
    EXPECT_EQ(s.render, RenderSettings{});
    EXPECT_TRUE(s.meshes.empty());
    ASSERT_EQ(s.punctualLights.size(), 1u);
    expectNear(s.punctualLights[0].intensity, {1, 1, 1});
}

TEST(SceneJson, CameraDefaultsUpAndFov) {
    const Scene s = test::parseInline(R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
                                          "lights": [{"type": "point", "position": [0, 0, 0], "intensity": 1}]})");
    expectNear(s.camera.up, {0, 1, 0});
    EXPECT_FLOAT_EQ(s.camera.fovYDeg, 45.0f);
}

TEST(SceneJson, ScaleAsVectorAndOverrideTypes) {
    const std::map<std::string, std::string> files{
        {"m/t.obj",
         "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\nusemtl b\nf 1 3 2\n"},
        {"m/t.mtl", "newmtl a\nKd 0.5 0.5 0.5\nnewmtl b\nKd 0.1 0.2 0.3\n"}};
    const Scene s = test::parseInline(R"({
        "meshes": [{"file": "m/t.obj", "transform": {"scale": [1, -2, 3]}}],
        "materials": {"a": {"type": "glass", "ior": 1.7, "transmittance": [0.9, 0.8, 0.7]},
                      "b": {"type": "mirror", "specular": 0.6, "diffuse": [0, 0, 0], "emission": [1, 2, 3]}}})",
                                      files);
    expectNear(s.meshes[0].transform.scale, {1, -2, 3});
    ASSERT_EQ(s.materials.size(), 2u);
    EXPECT_TRUE(s.materials[0].glass);
    EXPECT_FLOAT_EQ(s.materials[0].ior, 1.7f);
    expectNear(s.materials[0].transmittance, {0.9f, 0.8f, 0.7f});
    EXPECT_EQ(s.materials[1].reflection, Reflection::Mirror);
    EXPECT_FALSE(s.materials[1].glass);
    expectNear(s.materials[1].specular, {0.6f, 0.6f, 0.6f});
    expectNear(s.materials[1].emission, {1, 2, 3});
}

TEST(SceneJson, OverrideTextureIsRelativeToTheSceneFile) {
    DiskFileSource disk(test::testdataDir());
    const Scene s = parseScene(R"({"meshes": [{"file": "minimal/box.obj"}],
                                   "materials": {"lamp": {"texture": "minimal/checker.ppm"}}})",
                               "t.json", disk);
    ASSERT_EQ(s.textures.size(), 1u);  // shared with the floor's map_Kd
    EXPECT_EQ(s.materials[1].diffuseTexture, 0);
    EXPECT_EQ(s.textures[0].path, "minimal/checker.ppm");
}

TEST(SceneJson, AutoCameraFramesTheBoundsFromPlusZ) {
    const Scene s = test::parseInline(R"({"image": {"width": 100, "height": 100},
        "lights": [{"type": "point", "position": [-1, -1, -1], "intensity": 1},
                   {"type": "point", "position": [3, 3, 3], "intensity": 1}]})");
    expectNear(s.camera.lookAt, {1, 1, 1});
    expectNear(s.camera.up, {0, 1, 0});
    // Radius sqrt(12); the sphere fits 45 degrees: distance = r / sin(22.5 deg).
    const float distance = std::sqrt(12.0f) / std::sin(22.5f * 3.14159265f / 180.0f);
    expectNear(s.camera.position, {1, 1, 1 + distance}, 1e-4f);
    EXPECT_FLOAT_EQ(s.camera.fovYDeg, 45.0f);
    // Every corner of the bounds is inside the view cone.
    const glm::vec3 view = glm::normalize(s.camera.lookAt - s.camera.position);
    for (glm::vec3 corner :
         {glm::vec3(-1), glm::vec3(3), glm::vec3(-1, 3, 3), glm::vec3(3, -1, -1)}) {
        const float cosine = glm::dot(glm::normalize(corner - s.camera.position), view);
        EXPECT_GT(cosine, std::cos(22.5f * 3.14159265f / 180.0f));
    }
}

TEST(SceneJson, SpotAndDirectionalLights) {
    const Scene s = test::parseInline(R"({"lights": [
        {"type": "spot", "name": "s", "position": [0, 2, 0], "direction": [0, -2, 0],
         "intensity": [1, 2, 3], "inner_deg": 10, "outer_deg": 30},
        {"type": "directional", "name": "sun", "direction": [3, -4, 0], "irradiance": 5,
         "angle_deg": 0.5}]})");
    ASSERT_EQ(s.punctualLights.size(), 2u);
    const PunctualLight& spot = s.punctualLights[0];
    EXPECT_EQ(spot.kind, LightKind::Spot);
    EXPECT_EQ(spot.direction, glm::vec3(0, -1, 0));  // normalized
    EXPECT_EQ(spot.intensity, glm::vec3(1, 2, 3));
    EXPECT_FLOAT_EQ(spot.innerDeg, 10.0f);
    EXPECT_FLOAT_EQ(spot.outerDeg, 30.0f);
    const PunctualLight& sun = s.punctualLights[1];
    EXPECT_EQ(sun.kind, LightKind::Directional);
    EXPECT_NEAR(sun.direction.x, 0.6f, 1e-6f);
    EXPECT_NEAR(sun.direction.y, -0.8f, 1e-6f);
    EXPECT_EQ(sun.intensity, glm::vec3(5));
    EXPECT_FLOAT_EQ(sun.angleDeg, 0.5f);
    // A sun has no place: the bounds hold the spot alone.
    EXPECT_EQ(worldBounds(s).lo, glm::vec3(0, 2, 0));
    EXPECT_EQ(worldBounds(s).hi, glm::vec3(0, 2, 0));
}

TEST(SceneBounds, MeshesThroughTransformsAndLights) {
    Scene s;
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 1, 1}};
    m.transform.scale = glm::vec3(2.0f);
    m.transform.translate = {10, 0, 0};
    s.meshes.push_back(m);
    s.quadLights.push_back({"q", {0, 5, 0}, {1, 0, 0}, {0, 0, -1}, {1, 1, 1}});
    s.punctualLights.push_back(pointLight("p", {0, -7, 0}, {1, 1, 1}));
    const Bounds3 b = worldBounds(s);
    expectNear(b.lo, {0, -7, -1});
    expectNear(b.hi, {12, 5, 2});
    EXPECT_NEAR(b.diagonal(), glm::length(glm::vec3(12, 12, 3)), 1e-4f);
    EXPECT_TRUE(Bounds3{}.empty());
    EXPECT_EQ(Bounds3{}.diagonal(), 0.0f);
}

}  // namespace
}  // namespace igi
