// Every public test scene in /work/shared/scenes loads (or fails as it must).

#include <chrono>

#include <gtest/gtest.h>

#include <spdlog/spdlog.h>
#include "util/ExpectContains.h"

#include "scene/SceneBounds.h"
#include "scene/SceneLoader.h"
#include "scene/TestScenes.h"

namespace igi {
namespace {

#define REQUIRE_SHARED_SCENES()                  \
    const auto shared = test::sharedScenesDir(); \
    if (!shared) GTEST_SKIP() << "no shared scenes folder next to the project"

std::size_t triangleCount(const Scene& s) {
    std::size_t n = 0;
    for (const Mesh& m : s.meshes) n += m.triangles.size();
    return n;
}

bool anyEmissive(const Scene& s) {
    for (const Material& m : s.materials) {
        if (m.isEmissive()) return true;
    }
    return false;
}

// Structural sanity every loaded scene must have.
void expectConsistent(const Scene& s) {
    for (const Mesh& m : s.meshes) {
        ASSERT_EQ(m.materialIds.size(), m.triangles.size());
        EXPECT_TRUE(m.normals.empty() || m.normals.size() == m.positions.size());
        EXPECT_TRUE(m.uvs.empty() || m.uvs.size() == m.positions.size());
        for (const glm::uvec3& t : m.triangles) {
            for (int c = 0; c < 3; ++c) ASSERT_LT(t[c], m.positions.size());
        }
        for (std::uint32_t id : m.materialIds) ASSERT_LT(id, s.materials.size());
    }
    for (const Material& m : s.materials) {
        EXPECT_LT(m.diffuseTexture, static_cast<int>(s.textures.size()));
    }
    EXPECT_FALSE(worldBounds(s).empty());
}

TEST(SharedScenes, CornellBoxesLoadAsBareObjs) {
    REQUIRE_SHARED_SCENES();
    struct Case {
        const char* file;
        std::size_t triangles;  // 0: just some
        bool emitter;
    };
    const Case cases[] = {
        {"CornellBox-Original.obj", 36, true},
        {"CornellBox-Sphere.obj", 0, true},
        {"CornellBox-Water.obj", 0, true},
        {"CornellBox-Mirror.obj", 0, true},
        {"CornellBox-Empty-CO.obj", 0, true},
        {"CornellBox-Empty-RG.obj", 0, true},
        {"CornellBox-Empty-Squashed.obj", 0, true},
        {"CornellBox-Empty-White.obj", 0, true},
        {"water.obj", 0, false},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.file);
        SceneBundle bundle;
        const Scene s = loadSceneFile(*shared / "cornell-box" / c.file, &bundle);
        expectConsistent(s);
        if (c.triangles) {
            EXPECT_EQ(triangleCount(s), c.triangles);
        }
        EXPECT_EQ(anyEmissive(s), c.emitter);
        // A headlight exactly when there is no emitter.
        EXPECT_EQ(s.punctualLights.size(), c.emitter ? 0u : 1u);
        EXPECT_EQ(bundle.sceneText.find("headlight") != std::string::npos, !c.emitter);
    }
}

TEST(SharedScenes, CornellSphereMaterials) {
    REQUIRE_SHARED_SCENES();
    const Scene s = loadSceneFile(*shared / "cornell-box" / "CornellBox-Sphere.obj");
    bool mirror = false, glass = false;
    for (const Material& m : s.materials) {
        if (m.name == "leftSphere") mirror = m.reflection == Reflection::Mirror;
        if (m.name == "rightSphere")
            glass = m.glass && m.ior == 2.5f && m.transmittance == glm::vec3(1.0f);
    }
    EXPECT_TRUE(mirror);
    EXPECT_TRUE(glass);
    // The spheres have normals, the walls do not: one array, walls flat.
    EXPECT_EQ(s.meshes[0].normals.size(), s.meshes[0].positions.size());
}

// The glossy boxes' OBJs say `usemtl light`, which their MTL does not define: they load, with a
// warning naming the line, and their light is a grey material named 'light' (which emits
// nothing: a headlight lights them unless a scene file sets it, as
// common/scene/testdata/cornell-glossy.json does).
TEST(SharedScenes, GlossyCornellBoxesLackTheLightMaterial) {
    REQUIRE_SHARED_SCENES();
    for (const char* file : {"CornellBox-Glossy.obj", "CornellBox-Glossy-Floor.obj"}) {
        test::CapturedLog log;
        const Scene s = loadSceneFile(*shared / "cornell-box" / file);
        // Named as the user would find them, not relative to the scene folder.
        const std::string folder = (*shared / "cornell-box").string() + "/";
        EXPECT_CONTAINS(log.text(), folder + file +
                                        ":3009: usemtl 'light': no material of that name in " +
                                        folder + "CornellBox-Glossy.mtl");
        bool light = false;
        for (const Material& m : s.materials) light = light || m.name == "light";
        EXPECT_TRUE(light);
        EXPECT_EQ(s.punctualLights.size(), 1u) << "nothing emits: a headlight";
    }
    // With the Original's light set by a scene file, the box is lit by it.
    const Scene lit = loadSceneFile(test::testdataDir() / "cornell-glossy.json", test::trusted());
    for (const Material& m : lit.materials) {
        if (m.name == "light") {
            EXPECT_EQ(m.emission, glm::vec3(17, 12, 4));
        }
    }
    EXPECT_TRUE(lit.punctualLights.empty());
}

TEST(SharedScenes, MoriKnob) {
    REQUIRE_SHARED_SCENES();
    const Scene s = loadSceneFile(*shared / "mori-knob" / "testObj.obj");
    expectConsistent(s);
    EXPECT_TRUE(anyEmissive(s));
    EXPECT_TRUE(s.punctualLights.empty());
    bool outerGlass = false;
    for (const Material& m : s.materials) {
        if (m.name == "OuterMat") outerGlass = m.glass;
    }
    EXPECT_TRUE(outerGlass);
}

TEST(SharedScenes, BunnyGetsAHeadlight) {
    REQUIRE_SHARED_SCENES();
    const auto start = std::chrono::steady_clock::now();
    const Scene s = loadSceneFile(*shared / "stanford-bunny" / "bunny.obj");
    spdlog::info("bunny loaded in {:.3f} s",
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    expectConsistent(s);
    EXPECT_EQ(triangleCount(s), 144046u);
    EXPECT_EQ(s.meshes[0].normals.size(), s.meshes[0].positions.size());
    ASSERT_EQ(s.punctualLights.size(), 1u);
    EXPECT_EQ(s.punctualLights[0].name, "headlight");
    // Auto-framed: the camera looks at the centre of the mesh's bounds from +Z.
    Scene meshOnly = s;
    meshOnly.punctualLights.clear();
    const Bounds3 b = worldBounds(meshOnly);
    EXPECT_NEAR(s.camera.lookAt.x, b.centre().x, 1e-4f);
    EXPECT_GT(s.camera.position.z, b.hi.z);
}

TEST(SharedScenes, SponzaWithCaseMismatchedTextures) {
    REQUIRE_SHARED_SCENES();
    const auto start = std::chrono::steady_clock::now();
    SceneBundle bundle;
    const Scene s = loadSceneFile(test::testdataDir() / "sponza.json", &bundle, test::trusted());
    spdlog::info("sponza loaded in {:.3f} s",
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    expectConsistent(s);
    EXPECT_EQ(triangleCount(s), 66450u);
    EXPECT_GE(s.textures.size(), 10u);
    // 00_SKAP.JPG in the MTL is 00_skap.JPG on disk; the bundle holds the real name.
    EXPECT_EQ(bundle.files.count("../../../../shared/scenes/sponza-dabrovic/00_skap.JPG"), 1u);
    EXPECT_EQ(bundle.files.count("../../../../shared/scenes/sponza-dabrovic/00_SKAP.JPG"), 0u);
    for (const Texture& t : s.textures) {
        EXPECT_GT(t.width, 0);
        EXPECT_GT(t.average.x + t.average.y + t.average.z, 0.0f) << t.path;
    }
}

TEST(SharedScenes, GltfSamples) {
    REQUIRE_SHARED_SCENES();
    const Scene s = loadSceneFile(test::testdataDir() / "gltf-samples.json", test::trusted());
    expectConsistent(s);
    ASSERT_EQ(s.meshes.size(), 2u);
    // EmissiveStrengthTest: Emit4 is (0.1, 0.5, 0.9) x 4.
    bool emit4 = false;
    for (const Material& m : s.materials) {
        if (m.name == "Emit4")
            emit4 = glm::length(m.emission - glm::vec3(0.4f, 2.0f, 3.6f)) < 1e-5f;
    }
    EXPECT_TRUE(emit4);
    // LightsPunctualLamp: five point lights, moved with the mesh's transform.
    ASSERT_EQ(s.punctualLights.size(), 5u);
    EXPECT_EQ(s.punctualLights[0].name, "Point");
    EXPECT_NEAR(s.punctualLights[0].position.y, 0.9077973f - 3.0f, 1e-4f);
    EXPECT_NEAR(s.punctualLights[0].intensity.x, 15.0f / 683.0f, 1e-6f);  // candela / 683
    bool glass = false;
    for (const Material& m : s.materials) glass = glass || m.glass;
    EXPECT_TRUE(glass);
}

}  // namespace
}  // namespace igi
