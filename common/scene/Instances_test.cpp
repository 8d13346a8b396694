// Instancing (issue 36, item 3): a glTF primitive placed by several nodes, and an OBJ file
// named by several entries of the scene file, are loaded once and placed by instances.

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "scene/SceneBounds.h"
#include "scene/SceneLoader.h"
#include "scene/SceneState.h"
#include "scene/TestScenes.h"

namespace igi {
namespace {

void expectNear(glm::vec3 a, glm::vec3 b, float eps = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

glm::vec3 place(const glm::mat4& m, glm::vec3 p) {
    return glm::vec3(m * glm::vec4(p, 1.0f));
}

// plain.gltf's triangle (0,0,0), (1,0,0), (0,1,0) placed by `nodes` (each a node's JSON
// without its mesh), all of mesh 0; mesh 1, the same accessors with a red material, by the
// nodes of `redNodes`.
Scene placedTriangles(const std::vector<nlohmann::json>& nodes,
                      const std::vector<nlohmann::json>& redNodes = {}) {
    return test::plainGltfWith([&](nlohmann::json& g) {
        g["nodes"] = nlohmann::json::array();
        g["scenes"][0]["nodes"] = nlohmann::json::array();
        g["materials"] = {
            {{"name", "red"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 0, 0, 1}}}}}};
        g["meshes"].push_back(
            {{"primitives",
              {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"material", 0}}}}});
        auto add = [&](nlohmann::json node, int mesh) {
            node["mesh"] = mesh;
            g["scenes"][0]["nodes"].push_back(g["nodes"].size());
            g["nodes"].push_back(node);
        };
        for (const auto& n : nodes) add(n, 0);
        for (const auto& n : redNodes) add(n, 1);
    });
}

TEST(InstancedLoading, AGltfPrimitivePlacedByThreeNodesIsOneGeometryAndThreeInstances) {
    const Scene scene = placedTriangles(
        {{{"translation", {5, 0, 0}}},
         {{"rotation", {0, 0, 0.38268343, 0.92387953}}, {"scale", {2, 1, 3}}},  // 45 deg about z
         {{"translation", {0, 7, 0}}}});
    // The file's object, with no triangles of its own, and a part per node.
    ASSERT_EQ(scene.meshes.size(), 4u);
    const Mesh& object = scene.meshes[0];
    EXPECT_TRUE(object.triangles.empty());
    EXPECT_FALSE(object.instanced);
    EXPECT_EQ(object.partOf, -1);
    const Mesh& holder = scene.meshes[1];
    ASSERT_EQ(holder.triangles.size(), 1u);
    expectNear(holder.positions[holder.triangles[0].y], {1, 0, 0});  // in its own space
    for (std::size_t i = 1; i < 4; ++i) {
        const Mesh& part = scene.meshes[i];
        EXPECT_TRUE(part.instanced);
        EXPECT_EQ(part.partOf, 0);
        EXPECT_EQ(part.name, object.name);
        EXPECT_EQ(part.geometryOf, i == 1 ? -1 : 1);
        EXPECT_EQ(&geometryOf(scene, i), &holder);
        EXPECT_EQ(objectOf(scene, i), 0u);
        if (i > 1) {
            EXPECT_TRUE(part.positions.empty() && part.triangles.empty());
        }
    }
    // Each placed by its node's matrix.
    const SceneState state = SceneState::of(scene);
    expectNear(place(meshToWorld(scene, state.transforms, 1), {1, 0, 0}), {6, 0, 0});
    const float h = 0.70710678f;
    expectNear(place(meshToWorld(scene, state.transforms, 2), {1, 0, 0}), {2 * h, 2 * h, 0});
    expectNear(place(meshToWorld(scene, state.transforms, 2), {0, 1, 0}), {-h, h, 0});
    expectNear(place(meshToWorld(scene, state.transforms, 3), {0, 1, 0}), {0, 8, 0});
    // The bounds hold every placement.
    const Bounds3 b = worldBounds(scene);
    expectNear(b.hi, {6, 8, 0});
}

TEST(InstancedLoading, PlacementsWithAnotherMaterialShareTheGeometry) {
    // MetalRoughSpheresNoTextures' layout: a mesh per node, each with its own material, all
    // of the same accessors.
    const Scene scene = placedTriangles({{{"translation", {5, 0, 0}}}}, {{}});
    ASSERT_EQ(scene.meshes.size(), 3u);
    EXPECT_EQ(scene.meshes[2].geometryOf, 1);
    EXPECT_NE(scene.meshes[1].material, scene.meshes[2].material);
    EXPECT_EQ(scene.materials[std::size_t(scene.meshes[2].material)].name, "red");
    EXPECT_EQ(materialOf(scene, 2, 0), std::uint32_t(scene.meshes[2].material));
}

TEST(InstancedLoading, APrimitivePlacedOnceOrMirroredIsFlattenedAsBefore) {
    const Scene once = placedTriangles({{{"translation", {5, 0, 0}}}});
    ASSERT_EQ(once.meshes.size(), 1u);
    EXPECT_FALSE(once.meshes[0].instanced);
    expectNear(once.meshes[0].positions[1], {6, 0, 0});
    // A mirroring node turns its triangles in the loader: not an instance.
    const Scene mirrored = placedTriangles({{{"translation", {5, 0, 0}}}, {{"scale", {-1, 1, 1}}}});
    ASSERT_EQ(mirrored.meshes.size(), 1u);
    EXPECT_EQ(mirrored.meshes[0].triangles.size(), 2u);
}

TEST(InstancedLoading, AnObjFileNamedTwiceIsLoadedOnce) {
    const Scene scene = test::parseInline(
        R"({"meshes": [{"file": "t.obj", "name": "a"},
                       {"file": "t.obj", "name": "b", "transform": {"translate": [3, 0, 0]}},
                       {"file": "u.obj", "name": "c"}]})",
        {{"t.obj", test::kTriangle}, {"u.obj", test::kTriangle}});
    ASSERT_EQ(scene.meshes.size(), 3u);
    EXPECT_TRUE(scene.meshes[0].instanced);
    EXPECT_TRUE(scene.meshes[1].instanced);
    EXPECT_EQ(scene.meshes[1].geometryOf, 0);
    EXPECT_EQ(scene.meshes[1].partOf, -1);  // an object of its own, moved by its own name
    EXPECT_TRUE(scene.meshes[1].positions.empty());
    EXPECT_FALSE(scene.meshes[2].instanced);  // another file, loaded once
    EXPECT_EQ(scene.meshes[2].geometryOf, -1);
    const SceneState state = SceneState::of(scene);
    expectNear(place(meshToWorld(scene, state.transforms, 1), {1, 0, 0}), {4, 0, 0});
    expectNear(worldBounds(scene).hi, {4, 1, 0});
}

// Khronos' MetalRoughSpheresNoTextures: 98 nodes place one sphere (a material each), which
// flattened was 1,040,409 triangles.
TEST(InstancedLoading, MetalRoughSpheresAreOneSphereAndNinetyEightInstances) {
    const auto shared = test::sharedScenesDir();
    const auto file = shared ? *shared /
                                   "gltf/MetalRoughSpheresNoTextures/glTF/"
                                   "MetalRoughSpheresNoTextures.gltf"
                             : std::filesystem::path();
    if (!shared || !std::filesystem::exists(file)) GTEST_SKIP() << "no shared scenes";
    const Scene scene = loadSceneFile(file, test::trusted());
    std::size_t parts = 0, holders = 0, placed = 0, held = 0;
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
        const Mesh& m = scene.meshes[i];
        parts += m.partOf >= 0;
        holders += m.instanced && m.geometryOf < 0;
        placed += geometryOf(scene, i).triangles.size();
        held += m.triangles.size();
    }
    EXPECT_EQ(parts, 98u);
    EXPECT_EQ(holders, 1u);
    EXPECT_EQ(placed, 1'040'409u);  // what the flattened mesh had
    EXPECT_LT(held, 1'040'409u / 50);
}

}  // namespace
}  // namespace igi
