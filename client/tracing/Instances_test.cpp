// Instancing (issue 36, item 3): a geometry placed several times (Mesh::instanced) is one Embree
// scene that every placement instances, in the flat layout as in the instanced one; hits,
// normals and materials are those of the same triangles flattened into world space.

#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>

#include "scene/SceneState.h"
#include "testing/TestScenes.h"
#include "tracing/EmbreeDevice.h"
#include "tracing/MovedInstances.h"
#include "tracing/SceneGeometry.h"
#include "tracing/TraceableScene.h"

namespace igi {
namespace {

void expectNear(glm::vec3 a, glm::vec3 b, float eps, const char* what) {
    EXPECT_NEAR(a.x, b.x, eps) << what;
    EXPECT_NEAR(a.y, b.y, eps) << what;
    EXPECT_NEAR(a.z, b.z, eps) << what;
}

// The placements of the group's three parts: one translated, one turned 30 degrees about z
// and scaled non-uniformly, one translated with another material.
std::vector<glm::mat4> partMatrices() {
    glm::mat4 turned = glm::rotate(glm::mat4(1.0f), glm::radians(30.0f), glm::vec3(0, 0, 1));
    turned = glm::scale(turned, glm::vec3(1.0f, 2.0f, 0.5f));
    return {glm::translate(glm::mat4(1.0f), glm::vec3(-4, 0, 0)), turned,
            glm::translate(glm::mat4(1.0f), glm::vec3(4, 0, 0))};
}

// A glTF-like object: mesh 0 (no triangles of its own, as a glTF file whose nodes all place
// a shared primitive) and parts 1-3 placing one icosphere, the first holding it.
Scene groupScene(int subdivisions) {
    Scene scene;
    scene.materials = {testing::diffuse({0.8f, 0.8f, 0.8f}), testing::diffuse({0.8f, 0.1f, 0.1f})};
    Mesh object;
    object.name = "group";
    scene.meshes.push_back(object);
    const std::vector<glm::mat4> placed = partMatrices();
    for (std::size_t k = 0; k < placed.size(); ++k) {
        Mesh part =
            k == 0 ? testing::makeIcosphere(subdivisions, 1.0f, glm::vec3(0.0f), 0) : Mesh();
        part.name = "group";
        part.geometryOf = k == 0 ? -1 : 1;
        part.partOf = 0;
        part.material = k == 2 ? 1 : 0;
        part.local = placed[k];
        part.instanced = true;
        scene.meshes.push_back(std::move(part));
    }
    return scene;
}

// The same three placements flattened into world space, one plain mesh each.
Scene flattenedScene(int subdivisions) {
    Scene scene;
    scene.materials = {testing::diffuse({0.8f, 0.8f, 0.8f}), testing::diffuse({0.8f, 0.1f, 0.1f})};
    const Mesh sphere = testing::makeIcosphere(subdivisions, 1.0f, glm::vec3(0.0f), 0);
    const std::vector<glm::mat4> placed = partMatrices();
    for (std::size_t k = 0; k < placed.size(); ++k) {
        Mesh copy = sphere;
        const glm::mat3 normals = glm::transpose(glm::inverse(glm::mat3(placed[k])));
        for (glm::vec3& p : copy.positions) p = glm::vec3(placed[k] * glm::vec4(p, 1.0f));
        for (glm::vec3& n : copy.normals) n = glm::normalize(normals * n);
        copy.materialIds.assign(copy.triangles.size(), k == 2 ? 1u : 0u);
        scene.meshes.push_back(std::move(copy));
    }
    return scene;
}

TEST(InstancedTracing, OneEmbreeSceneHoldsTheSharedGeometry) {
    const Scene scene = groupScene(1);
    EmbreeDevice device;
    SceneGeometry geometry(device, scene);
    EXPECT_EQ(geometry.mesh(0), nullptr);  // the object has no triangles of its own
    ASSERT_NE(geometry.mesh(1), nullptr);
    EXPECT_EQ(geometry.mesh(2), geometry.mesh(1));
    EXPECT_EQ(geometry.mesh(3), geometry.mesh(1));
    EXPECT_EQ(geometry.instancedSceneCount(), 1u);
    // 80 triangles built once, placed three times.
    EXPECT_EQ(geometry.builtTriangleCount(), 80u);
    EXPECT_EQ(geometry.triangleCount(), 240u);
    TraceableScene traceable(geometry);
    EXPECT_EQ(traceable.layout(), SceneLayout::Flat);
    EXPECT_EQ(traceable.triangleCount(), 240u);
}

// Rays down the z axis over the three placements hit the instanced scene where they hit the
// flattened one, with the same normals (the non-uniform scale's by the inverse transpose), the
// same material, and the placement's mesh.
TEST(InstancedTracing, HitsAreThoseOfTheFlattenedTriangles) {
    const Scene instanced = groupScene(2), flat = flattenedScene(2);
    EmbreeDevice device;
    SceneGeometry gi(device, instanced), gf(device, flat);
    TraceableScene ti(gi), tf(gf);
    RayCounters counters;
    int hits = 0, grazing = 0, perPart[3] = {0, 0, 0};
    // A grid off the vertices' coordinates: a ray along a silhouette may hit in one and miss
    // in the other by rounding, and is counted, not compared.
    for (float x = -5.3f + 0.0123f; x <= 5.3f; x += 0.05f) {
        for (float y = -2.3f + 0.0071f; y <= 2.3f; y += 0.05f) {
            const glm::vec3 origin(x, y, 10.0f), direction(0.0f, 0.0f, -1.0f);
            SurfacePoint a, b;
            const bool ha = ti.intersect(origin, direction, 100.0f, a, counters);
            const bool hb = tf.intersect(origin, direction, 100.0f, b, counters);
            if (ha != hb) ++grazing;
            if (!ha || !hb) continue;
            ++hits;
            ASSERT_EQ(a.mesh, b.mesh + 1) << x << ", " << y;  // parts 1-3, meshes 0-2
            ++perPart[b.mesh];
            EXPECT_EQ(a.triangle, b.triangle);
            EXPECT_EQ(a.material->diffuse, b.material->diffuse);
            expectNear(a.position, b.position, 1e-4f, "position");
            expectNear(a.geometricNormal, b.geometricNormal, 1e-4f, "geometric normal");
            expectNear(a.shadingNormal, b.shadingNormal, 1e-4f, "shading normal");
            EXPECT_NEAR(a.distance, b.distance, 1e-4f);
            if (::testing::Test::HasFailure()) return;
        }
    }
    EXPECT_LE(grazing, 2);
    EXPECT_GT(hits, 2000);
    for (int n : perPart) EXPECT_GT(n, 300);
    // The turned, stretched one: its top is at z = 0.5 (scaled by 0.5), as is the hit there.
    SurfacePoint top;
    ASSERT_TRUE(ti.intersect({0.0f, 0.0f, 10.0f}, {0.0f, 0.0f, -1.0f}, 100.0f, top, counters));
    EXPECT_EQ(top.mesh, 2u);
    EXPECT_NEAR(top.position.z, 0.5f, 0.01f);
    EXPECT_GT(top.shadingNormal.z, 0.97f);
    // A point on its flank: the normal of an ellipsoid of semi-axes (1, 2, 0.5) turned 30
    // degrees, (x / a^2, y / b^2, z / c^2) in its own frame, up to the icosphere's facets.
    const float c = std::cos(glm::radians(30.0f)), s = std::sin(glm::radians(30.0f));
    const glm::vec3 along(-s, c, 0.0f);  // the stretched axis, in the world
    SurfacePoint flank;
    ASSERT_TRUE(
        ti.intersect(1.2f * along + glm::vec3(0, 0, 10), {0, 0, -1}, 100.0f, flank, counters));
    EXPECT_EQ(flank.mesh, 2u);
    const glm::vec3 local(c * flank.position.x + s * flank.position.y,
                          -s * flank.position.x + c * flank.position.y, flank.position.z);
    const glm::vec3 expectedLocal =
        glm::normalize(glm::vec3(local.x, local.y / 4.0f, local.z / 0.25f));
    const glm::vec3 expected(c * expectedLocal.x - s * expectedLocal.y,
                             s * expectedLocal.x + c * expectedLocal.y, expectedLocal.z);
    EXPECT_GT(glm::dot(flank.shadingNormal, expected), 0.995f);
}

// Two objects placing one geometry (an OBJ file named twice by the scene file): moving one
// moves only it, in the flat layout (small scenes) and the instanced one (large ones).
TEST(InstancedTracing, MovingOneInstanceMovesOnlyIt) {
    for (int subdivisions : {1, 6}) {
        Scene scene;
        scene.materials = {testing::diffuse({0.8f, 0.8f, 0.8f})};
        Mesh first = testing::makeIcosphere(subdivisions, 1.0f, glm::vec3(0.0f), 0);
        first.instanced = true;
        first.transform.translate = {-2, 0, 0};
        Mesh second;
        second.geometryOf = 0;
        second.instanced = true;
        second.transform.translate = {2, 0, 0};
        scene.meshes = {first, second};
        EmbreeDevice device;
        SceneGeometry geometry(device, scene);
        EXPECT_EQ(geometry.mesh(0), geometry.mesh(1));
        const SceneState before = SceneState::of(scene);
        SceneState after = before;
        after.transforms[1].translate = {2, 3, 0};
        TraceableScene moved(geometry, after);
        EXPECT_EQ(moved.layout(), subdivisions == 6 ? SceneLayout::Instanced : SceneLayout::Flat);
        RayCounters counters;
        SurfacePoint hit;
        const glm::vec3 down(0, 0, -1);
        ASSERT_TRUE(moved.intersect({-2, 0, 10}, down, 100.0f, hit, counters));
        EXPECT_EQ(hit.mesh, 0u);
        expectNear(hit.position, {-2, 0, 1}, 0.01f, "the unmoved one");
        EXPECT_FALSE(moved.intersect({2, 0, 10}, down, 100.0f, hit, counters));
        ASSERT_TRUE(moved.intersect({2, 3, 10}, down, 100.0f, hit, counters));
        EXPECT_EQ(hit.mesh, 1u);
        expectNear(hit.position, {2, 3, 1}, 0.01f, "the moved one");
        const MovedInstances changed(geometry, before, after);
        EXPECT_FALSE(changed.meshMoved(0));
        EXPECT_TRUE(changed.meshMoved(1));
        EXPECT_TRUE(changed.occluded(true, {2, 0, 10}, down, 100.0f, counters));
        EXPECT_FALSE(changed.occluded(false, {2, 0, 10}, down, 100.0f, counters));
        EXPECT_FALSE(changed.occluded(false, {-2, 0, 10}, down, 100.0f, counters));
    }
}

// The parts of an object follow its transform (a glTF file moved by a command moves all of
// its nodes), each keeping its own placement.
TEST(InstancedTracing, MovingTheObjectMovesEveryPart) {
    const Scene scene = groupScene(1);
    EmbreeDevice device;
    SceneGeometry geometry(device, scene);
    const SceneState before = SceneState::of(scene);
    SceneState after = before;
    after.transforms[0].translate = {0, 10, 0};
    TraceableScene moved(geometry, after);
    RayCounters counters;
    SurfacePoint hit;
    const glm::vec3 down(0, 0, -1);
    for (float x : {-4.0f, 0.0f, 4.0f}) {
        EXPECT_FALSE(moved.intersect({x, 0, 10}, down, 100.0f, hit, counters)) << x;
        ASSERT_TRUE(moved.intersect({x, 10, 10}, down, 100.0f, hit, counters)) << x;
        EXPECT_EQ(hit.mesh, x < 0 ? 1u : x > 0 ? 3u : 2u);
    }
    const MovedInstances changed(geometry, before, after);
    for (std::uint32_t m = 1; m <= 3; ++m) EXPECT_TRUE(changed.meshMoved(m)) << m;
}

}  // namespace
}  // namespace igi
