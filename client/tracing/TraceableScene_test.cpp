#include "tracing/TraceableScene.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "testing/TestScenes.h"
#include "tracing/EmbreeDevice.h"
#include "tracing/SceneGeometry.h"

namespace igi {
namespace {

// Origins inside the unit box; targets inside or beyond its walls, so that the walls, the block
// and the glass ball all stand in the way of some rays.
struct RandomRays {
    std::mt19937 random{7};
    std::uniform_real_distribution<float> inside{0.05f, 0.95f}, around{-0.3f, 1.3f}, unit{0, 1};

    glm::vec3 origin() { return {inside(random), inside(random), inside(random)}; }
    TraceableScene::ShadowRay shadowRay(glm::vec3 origin) {
        const glm::vec3 target(around(random), around(random), around(random));
        return {origin, glm::normalize(target - origin),
                glm::length(target - origin) * (0.2f + 0.8f * unit(random))};
    }
};

// Packets must answer exactly as single rays do: the integrator uses both, and an image must
// not depend on which one a shadow ray went through, nor on the packets' width.
TEST(TraceableScene, PacketsOfShadowRaysAnswerAsSingleRaysDo) {
    const Scene scene = testing::cornellBox(1.0f, true);
    EmbreeDevice device;
    SceneGeometry geometry(device, scene);
    TraceableScene traceable(geometry);
    for (int width : {8, 16}) {
        traceable.setPacketWidth(width);
        RandomRays rays;
        RayCounters single, packed;
        int blockedCount = 0, freeCount = 0;
        for (int round = 0; round < 2000; ++round) {
            // Partial packets too; one origin for all rays, or one per ray (packets by target).
            const int count = 1 + round % TraceableScene::kMaxPacket;
            const glm::vec3 shared = rays.origin();
            TraceableScene::ShadowRay packet[TraceableScene::kMaxPacket];
            for (int i = 0; i < count; ++i)
                packet[i] = rays.shadowRay(round % 2 ? shared : rays.origin());
            bool blocked[TraceableScene::kMaxPacket];
            traceable.occludedPacket(packet, count, blocked, packed);
            for (int i = 0; i < count; ++i) {
                const auto& r = packet[i];
                const bool expected = traceable.occluded(r.origin, r.direction, r.tfar, single);
                ASSERT_EQ(blocked[i], expected) << "width " << width << ", round " << round;
                (expected ? blockedCount : freeCount)++;
            }
        }
        // Both outcomes occur often, or the comparison proves little.
        EXPECT_GT(blockedCount, 3000);
        EXPECT_GT(freeCount, 3000);
        EXPECT_EQ(packed.shadowRays, single.shadowRays);
        EXPECT_EQ(packed.rays, single.rays);
    }
}

TEST(TraceableScene, PacketsOfClosestHitRaysFindWhatSingleRaysFind) {
    const Scene scene = testing::cornellBox(1.0f, true);
    EmbreeDevice device;
    SceneGeometry geometry(device, scene);
    TraceableScene traceable(geometry);
    for (int width : {8, 16}) {
        traceable.setPacketWidth(width);
        RandomRays rays;
        RayCounters single, packed;
        int hits = 0, misses = 0;
        for (int round = 0; round < 500; ++round) {
            const int count = 1 + round % TraceableScene::kMaxPacket;
            glm::vec3 origins[TraceableScene::kMaxPacket], directions[TraceableScene::kMaxPacket];
            float tfar[TraceableScene::kMaxPacket];
            // Every other packet is coherent (one origin, one octant) as eye rays are, which
            // Embree traces in another way; the others have random origins and directions.
            const bool coherent = round % 2 == 0;
            const glm::vec3 shared = rays.origin();
            for (int i = 0; i < count; ++i) {
                const auto r = rays.shadowRay(coherent ? shared : rays.origin());
                origins[i] = r.origin;
                directions[i] = coherent ? glm::abs(r.direction) : r.direction;
                tfar[i] = round % 3 ? INFINITY : r.tfar;  // misses inside the box too
            }
            SurfacePoint found[TraceableScene::kMaxPacket];
            bool hit[TraceableScene::kMaxPacket];
            traceable.intersectPacket(origins, directions, tfar, count, found, hit, packed);
            for (int i = 0; i < count; ++i) {
                SurfacePoint expected;
                const bool expectHit =
                    traceable.intersect(origins[i], directions[i], tfar[i], expected, single);
                ASSERT_EQ(hit[i], expectHit) << "width " << width << ", round " << round;
                (expectHit ? hits : misses)++;
                if (!expectHit) continue;
                EXPECT_EQ(found[i].mesh, expected.mesh);
                EXPECT_EQ(found[i].triangle, expected.triangle);
                EXPECT_EQ(found[i].material, expected.material);
                EXPECT_FLOAT_EQ(found[i].distance, expected.distance);
                EXPECT_EQ(found[i].shadingNormal, expected.shadingNormal);
            }
        }
        EXPECT_GT(hits, 1000);
        EXPECT_GT(misses, 300);
        EXPECT_EQ(packed.rays, single.rays);
    }
}

// The light-edge rays ask a packet for what its hits emit only (HitDetail::Emission): that
// part is what the full fill gives, on a textured scene (the fill of one without textures is
// always whole), while the albedo, which such hits skip, is left as it was.
TEST(TraceableScene, APacketFilledForEmissionFindsWhatTheFullFillEmits) {
    Scene scene;
    Texture stripes;  // 4 x 1 texels along u: two bright, two dark
    stripes.path = "stripes";
    stripes.width = 4;
    stripes.height = 1;
    stripes.texels = {glm::vec3(1.0f), glm::vec3(0.8f), glm::vec3(0.1f), glm::vec3(0.0f)};
    stripes.average = glm::vec3(0.475f);
    scene.textures.push_back(stripes);
    Material floor = testing::diffuse(glm::vec3(0.7f));
    floor.diffuseTexture = 0;
    Material screen = testing::diffuse(glm::vec3(0.0f));
    screen.emission = glm::vec3(4.0f);
    screen.emissionTexture = 0;
    scene.materials = {floor, screen};
    Mesh ground = testing::makeQuad({-2, -2, 0}, {4, 0, 0}, {0, 4, 0}, 0);  // faces +z
    ground.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    Mesh emitter = testing::makeQuad({-1, -1, 1.5f}, {0, 2, 0}, {2, 0, 0}, 1);  // faces -z
    emitter.uvs = {{0, 0}, {0, 0}, {1, 0}, {1, 0}};
    scene.meshes = {ground, emitter};
    EmbreeDevice device;
    SceneGeometry geometry(device, scene);
    TraceableScene traceable(geometry);
    std::mt19937 random(11);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    int emitters = 0, floors = 0;
    for (int round = 0; round < 100; ++round) {
        const int count = 2 + round % (TraceableScene::kMaxPacket - 1);
        glm::vec3 origins[TraceableScene::kMaxPacket], directions[TraceableScene::kMaxPacket];
        float tfar[TraceableScene::kMaxPacket];
        for (int i = 0; i < count; ++i) {  // from between the two, up or down
            origins[i] = glm::vec3(0.5f * unit(random), 0.5f * unit(random), 0.7f);
            directions[i] =
                glm::normalize(glm::vec3(unit(random), unit(random), i % 2 ? 1.0f : -1.0f));
            tfar[i] = INFINITY;
        }
        SurfacePoint full[TraceableScene::kMaxPacket], emission[TraceableScene::kMaxPacket];
        bool foundFull[TraceableScene::kMaxPacket], foundEmission[TraceableScene::kMaxPacket];
        RayCounters counters;
        traceable.intersectPacket(origins, directions, tfar, count, full, foundFull, counters);
        traceable.intersectPacket(origins, directions, tfar, count, emission, foundEmission,
                                  counters, TraceableScene::HitDetail::Emission);
        for (int i = 0; i < count; ++i) {
            ASSERT_EQ(foundEmission[i], foundFull[i]);
            if (!foundFull[i]) continue;
            EXPECT_EQ(emission[i].material, full[i].material);
            EXPECT_EQ(emission[i].position, full[i].position);
            EXPECT_EQ(emission[i].geometricNormal, full[i].geometricNormal);
            EXPECT_EQ(emission[i].emissionTexel, full[i].emissionTexel);
            EXPECT_EQ(emission[i].albedo, glm::vec3(0.0f));  // not filled
            (full[i].material->isEmissive() ? emitters : floors)++;
        }
    }
    EXPECT_GT(emitters, 200);
    EXPECT_GT(floors, 200);
}

// A small scene is flat in every state; a large one is flat where its objects stand as loaded
// and instanced once one moved. Both layouts find the same surfaces at the same scale.
TEST(TraceableScene, FlatAndInstancedLayoutsFindTheSameSurfaces) {
    Scene scene = testing::cornellBox(1.0f, true);
    // Pad the scene past the rebuild limit with a mesh far behind the box: it blocks no ray.
    Mesh filler;
    filler.name = "filler";
    const auto triangles = std::uint32_t(SceneGeometry::kFlatRebuildTriangles);
    for (std::uint32_t t = 0; t < triangles; ++t) {
        const float x = float(t % 256) * 0.01f, y = float(t / 256) * 0.01f;
        const auto base = std::uint32_t(filler.positions.size());
        filler.positions.insert(filler.positions.end(),
                                {{x, y, -50.0f}, {x + 0.01f, y, -50.0f}, {x, y + 0.01f, -50.0f}});
        filler.triangles.push_back({base, base + 1, base + 2});
        filler.materialIds.push_back(0);
    }
    scene.meshes.push_back(filler);
    EmbreeDevice device;
    SceneGeometry geometry(device, scene);
    const SceneState loaded = SceneState::of(scene);
    SceneState moved = loaded;
    moved.transforms.back().translate += glm::vec3(0.0f, 0.0f, -1.0f);  // the filler moves away
    moved.transforms.back().translate -= glm::vec3(0.0f, 0.0f, -1.0f);  // ... and back: as loaded
    ASSERT_EQ(geometry.layoutOf(moved), SceneLayout::Flat);
    moved.transforms.back().translate += glm::vec3(0.0f, 0.0f, -1.0f);
    ASSERT_EQ(geometry.layoutOf(moved), SceneLayout::Instanced);

    TraceableScene flat(geometry, loaded), instanced(geometry, moved);
    ASSERT_EQ(flat.layout(), SceneLayout::Flat);
    ASSERT_EQ(instanced.layout(), SceneLayout::Instanced);
    EXPECT_GT(flat.diagonal(), 50.0f);
    RandomRays rays;
    RayCounters counters;
    int hits = 0;
    for (int round = 0; round < 4000; ++round) {
        const auto r = rays.shadowRay(rays.origin());
        SurfacePoint a, b;
        const bool hitA = flat.intersect(r.origin, r.direction, INFINITY, a, counters);
        const bool hitB = instanced.intersect(r.origin, r.direction, INFINITY, b, counters);
        ASSERT_EQ(hitA, hitB) << "round " << round;
        if (!hitA || a.mesh != b.mesh || a.triangle != b.triangle) continue;  // an edge
        ++hits;
        EXPECT_NEAR(a.distance, b.distance, 1e-5f);
        EXPECT_LT(glm::length(a.position - b.position), 1e-5f);
    }
    EXPECT_GT(hits, 2000);
}

}  // namespace
}  // namespace igi

namespace igi {
namespace {

// A rough GGX metal whose roughness map is 0 on some texels: those texels are mirrors, so its
// triangles must be caustic targets (review of issue 34: the factor alone hid them).
TEST(TraceableScene, AGgxMaterialWithMirrorTexelsIsASpecularTarget) {
    Scene scene;
    Material metal = testing::diffuse(glm::vec3(0.8f));
    metal.reflection = Reflection::Ggx;
    metal.metallic = 1.0f;
    metal.roughness = 1.0f;
    scene.materials.push_back(metal);
    scene.meshes.push_back(testing::makeQuad({-1, 0, -1}, {0, 0, 2}, {2, 0, 0}, 0));
    EmbreeDevice device;
    {
        SceneGeometry geometry(device, scene);
        EXPECT_TRUE(TraceableScene(geometry).specularTriangles().empty());
    }
    Texture map;
    map.width = 2;
    map.height = 1;
    map.texels = {glm::vec3(0, 0.0f, 1), glm::vec3(0, 1.0f, 1)};  // green: roughness
    map.minimum = glm::vec3(0.0f, 0.0f, 1.0f);
    scene.textures.push_back(map);
    scene.materials[0].metallicRoughnessTexture = 0;
    SceneGeometry geometry(device, scene);
    EXPECT_EQ(TraceableScene(geometry).specularTriangles().size(), 2u);
}

}  // namespace
}  // namespace igi
