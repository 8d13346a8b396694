// A scene rebuilt from its bundle (what a client receives) equals the one loaded from disk.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "scene/SceneLoader.h"
#include "scene/TestScenes.h"

namespace igi {
namespace {

void expectSameMaterial(const Material& a, const Material& b) {
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.diffuse, b.diffuse);
    EXPECT_EQ(a.diffuseTexture, b.diffuseTexture);
    EXPECT_EQ(a.specular, b.specular);
    EXPECT_EQ(a.phongExponent, b.phongExponent);
    EXPECT_EQ(a.reflection, b.reflection);
    EXPECT_EQ(a.glass, b.glass);
    EXPECT_EQ(a.ior, b.ior);
    EXPECT_EQ(a.transmittance, b.transmittance);
    EXPECT_EQ(a.emission, b.emission);
}

void expectSameScene(const Scene& a, const Scene& b) {
    EXPECT_EQ(a.camera, b.camera);
    EXPECT_EQ(a.image.width, b.image.width);
    EXPECT_EQ(a.image.height, b.image.height);
    EXPECT_EQ(a.image.exposure, b.image.exposure);
    EXPECT_EQ(a.render, b.render);
    ASSERT_EQ(a.meshes.size(), b.meshes.size());
    for (std::size_t i = 0; i < a.meshes.size(); ++i) {
        EXPECT_EQ(a.meshes[i].name, b.meshes[i].name);
        EXPECT_EQ(a.meshes[i].transform, b.meshes[i].transform);
        EXPECT_EQ(a.meshes[i].positions, b.meshes[i].positions);
        EXPECT_EQ(a.meshes[i].normals, b.meshes[i].normals);
        EXPECT_EQ(a.meshes[i].uvs, b.meshes[i].uvs);
        EXPECT_EQ(a.meshes[i].triangles, b.meshes[i].triangles);
        EXPECT_EQ(a.meshes[i].materialIds, b.meshes[i].materialIds);
        // Instancing: the clients' meshes are placed as the master's.
        EXPECT_EQ(a.meshes[i].geometryOf, b.meshes[i].geometryOf);
        EXPECT_EQ(a.meshes[i].partOf, b.meshes[i].partOf);
        EXPECT_EQ(a.meshes[i].material, b.meshes[i].material);
        EXPECT_EQ(a.meshes[i].local, b.meshes[i].local);
        EXPECT_EQ(a.meshes[i].instanced, b.meshes[i].instanced);
    }
    ASSERT_EQ(a.materials.size(), b.materials.size());
    for (std::size_t i = 0; i < a.materials.size(); ++i)
        expectSameMaterial(a.materials[i], b.materials[i]);
    ASSERT_EQ(a.textures.size(), b.textures.size());
    for (std::size_t i = 0; i < a.textures.size(); ++i) {
        EXPECT_EQ(a.textures[i].path, b.textures[i].path);
        EXPECT_EQ(a.textures[i].width, b.textures[i].width);
        EXPECT_EQ(a.textures[i].height, b.textures[i].height);
        EXPECT_EQ(a.textures[i].texels, b.textures[i].texels);
        EXPECT_EQ(a.textures[i].codes, b.textures[i].codes);
        EXPECT_EQ(a.textures[i].table, b.textures[i].table);
        EXPECT_EQ(a.textures[i].average, b.textures[i].average);
    }
    ASSERT_EQ(a.punctualLights.size(), b.punctualLights.size());
    for (std::size_t i = 0; i < a.punctualLights.size(); ++i) {
        EXPECT_EQ(a.punctualLights[i].name, b.punctualLights[i].name);
        EXPECT_EQ(a.punctualLights[i].position, b.punctualLights[i].position);
        EXPECT_EQ(a.punctualLights[i].intensity, b.punctualLights[i].intensity);
    }
    ASSERT_EQ(a.quadLights.size(), b.quadLights.size());
    for (std::size_t i = 0; i < a.quadLights.size(); ++i) {
        EXPECT_EQ(a.quadLights[i].corner, b.quadLights[i].corner);
        EXPECT_EQ(a.quadLights[i].edge1, b.quadLights[i].edge1);
        EXPECT_EQ(a.quadLights[i].edge2, b.quadLights[i].edge2);
        EXPECT_EQ(a.quadLights[i].radiance, b.quadLights[i].radiance);
    }
}

void expectRoundTrip(const std::filesystem::path& path,
                     const SceneLoadOptions& options = SceneLoadOptions()) {
    SCOPED_TRACE(path.string());
    SceneBundle bundle;
    const Scene fromDisk = loadSceneFile(path, &bundle, options);
    EXPECT_EQ(bundle.sceneName, path.filename().string());
    EXPECT_FALSE(bundle.files.empty());
    const Scene fromBundle = loadSceneBundle(bundle);
    expectSameScene(fromDisk, fromBundle);
}

TEST(SceneBundle, MinimalSceneRoundTrips) {
    SceneBundle bundle;
    loadSceneFile(test::testdataDir() / "minimal" / "scene.json", &bundle);
    // Exactly the files the scene references, keyed relative to the scene file.
    std::vector<std::string> keys;
    for (const auto& [k, v] : bundle.files) keys.push_back(k);
    EXPECT_EQ(keys, (std::vector<std::string>{"box.mtl", "box.obj", "checker.ppm"}));
    expectRoundTrip(test::testdataDir() / "minimal" / "scene.json");
}

TEST(SceneBundle, GltfRoundTrips) {
    expectRoundTrip(test::testdataDir() / "gltf" / "scene.json");
}

TEST(SceneBundle, SharedScenesRoundTrip) {
    const auto shared = test::sharedScenesDir();
    if (!shared) GTEST_SKIP() << "no shared scenes folder next to the project";
    expectRoundTrip(*shared / "cornell-box" / "CornellBox-Sphere.obj");
    expectRoundTrip(*shared / "cornell-box" / "water.obj");  // with a headlight
    // Case-mismatched textures; both files reach ../shared/scenes.
    expectRoundTrip(test::testdataDir() / "sponza.json", test::trusted());
    expectRoundTrip(test::testdataDir() / "gltf-samples.json", test::trusted());
}

// A bare glTF is a scene as a bare OBJ is: the model, auto-framed, with a headlight only when
// nothing in it emits.
TEST(SceneLoader, BareGltfIsAScene) {
    const auto lit = test::testdataDir() / "gltf" / "triangle.gltf";
    const Scene withLamp = loadSceneFile(lit);
    ASSERT_EQ(withLamp.punctualLights.size(), 3u);  // a point, a spot and a sun
    EXPECT_EQ(withLamp.punctualLights[0].name, "lamp");
    expectRoundTrip(lit);

    const auto plain = test::testdataDir() / "gltf" / "plain.gltf";
    SceneBundle bundle;
    const Scene dark = loadSceneFile(plain, &bundle);
    ASSERT_EQ(dark.punctualLights.size(), 1u);
    EXPECT_EQ(dark.punctualLights[0].name, "headlight");
    EXPECT_NE(bundle.sceneText.find("headlight"), std::string::npos);
    expectRoundTrip(plain);
}

// Issue 40 (igi-master --headlight): a headlight beside the scene's own lights, the same on
// every client; and a scene's lights are known, lit or not.
TEST(SceneLoader, AHeadlightOnRequestReachesTheClientsToo) {
    const auto dir =
        std::filesystem::temp_directory_path() / ("igi-headlight-" + std::to_string(getpid()));
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "box.obj") << "v -1 0 -1\nv 1 0 -1\nv 0 0 1\nf 1 3 2\n";
    std::ofstream(dir / "scene.json") << R"({"meshes": [{"file": "box.obj"}],
        "lights": [{"type": "point", "position": [0, 2, 0], "intensity": [1, 1, 1]}]})";
    SceneLoadOptions options;
    options.headlight = true;
    SceneBundle bundle;
    const Scene lit = loadSceneFile(dir / "scene.json", &bundle, options);
    EXPECT_TRUE(sceneHasHeadlight(lit));
    EXPECT_EQ(lit.punctualLights.size(), 2u);
    EXPECT_TRUE(sceneHasHeadlight(loadSceneBundle(bundle)));
    expectRoundTrip(dir / "scene.json", options);
    EXPECT_FALSE(sceneHasHeadlight(loadSceneFile(dir / "scene.json")));
    EXPECT_TRUE(sceneHasEmitter(loadSceneFile(dir / "scene.json")));

    std::ofstream(dir / "dark.json") << R"({"meshes": [{"file": "box.obj"}], "lights": []})";
    EXPECT_FALSE(sceneHasEmitter(loadSceneFile(dir / "dark.json")));
    // A bare model without an emitter has one already: not a second.
    const Scene plain = loadSceneFile(test::testdataDir() / "gltf" / "plain.gltf", options);
    EXPECT_EQ(plain.punctualLights.size(), 1u);
    std::filesystem::remove_all(dir);
}

/// `text` read whole from `path`.
std::string readAll(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

// The same plain model as a binary glTF (its buffer in the GLB's BIN chunk) is a scene too.
TEST(SceneLoader, BareGlbIsAScene) {
    const auto dir = test::testdataDir() / "gltf";
    std::string json = readAll(dir / "plain.gltf");
    const std::string uri = R"("uri": "plain.bin",)";
    const auto at = json.find(uri);
    ASSERT_NE(at, std::string::npos) << "plain.gltf names its buffer differently";
    json.erase(at, uri.size());  // a buffer without uri is the GLB's BIN chunk
    std::string bin = readAll(dir / "plain.bin");
    while (json.size() % 4) json += ' ';
    while (bin.size() % 4) bin += '\0';
    auto u32 = [](std::uint32_t v) {
        std::string b(4, '\0');
        for (int i = 0; i < 4; ++i) b[i] = char(v >> (8 * i));
        return b;
    };
    const auto length = std::uint32_t(12 + 8 + json.size() + 8 + bin.size());
    const std::string glb = "glTF" + u32(2) + u32(length) + u32(std::uint32_t(json.size())) +
                            "JSON" + json + u32(std::uint32_t(bin.size())) +
                            std::string("BIN\0", 4) + bin;
    const auto path = std::filesystem::temp_directory_path() /
                      ("igi-bare-glb-" + std::to_string(::getpid()) + ".glb");
    std::ofstream(path, std::ios::binary) << glb;
    SceneBundle bundle;
    const Scene scene = loadSceneFile(path, &bundle);
    std::filesystem::remove(path);
    const Scene gltf = loadSceneFile(dir / "plain.gltf");
    ASSERT_EQ(scene.meshes.size(), gltf.meshes.size());
    EXPECT_EQ(scene.meshes[0].positions, gltf.meshes[0].positions);
    EXPECT_EQ(scene.meshes[0].triangles, gltf.meshes[0].triangles);
    ASSERT_EQ(scene.punctualLights.size(), 1u);
    EXPECT_EQ(scene.punctualLights[0].name, "headlight");
    EXPECT_EQ(scene.camera.position, gltf.camera.position) << "auto-framed the same way";
}

TEST(SceneLoader, BareSharedGltfScenes) {
    const auto shared = test::sharedScenesDir();
    if (!shared) GTEST_SKIP() << "no shared scenes folder next to the project";
    const auto emissive = *shared / "gltf" / "EmissiveStrengthTest" / "glTF";
    SceneBundle bundle;
    const Scene lit = loadSceneFile(emissive / "EmissiveStrengthTest.gltf", &bundle);
    EXPECT_TRUE(lit.punctualLights.empty()) << "emissive cubes light it: no headlight";
    EXPECT_EQ(bundle.sceneText.find("headlight"), std::string::npos);
    expectRoundTrip(emissive / "EmissiveStrengthTest.gltf");
    expectRoundTrip(*shared / "gltf" / "LightsPunctualLamp" / "glTF" / "LightsPunctualLamp.gltf");
}

TEST(SceneBundle, AMissingFileInTheBundleIsAnError) {
    SceneBundle bundle;
    loadSceneFile(test::testdataDir() / "minimal" / "scene.json", &bundle);
    bundle.files.erase("box.mtl");
    const std::string what = test::sceneErrorOf([&] { loadSceneBundle(bundle); });
    EXPECT_NE(what.find("box.obj:3: material library 'box.mtl' not found"), std::string::npos)
        << what;
}

TEST(SceneLoader, UnsupportedSceneFileType) {
    const std::string what =
        test::sceneErrorOf([] { loadSceneFile(test::testdataDir() / "minimal" / "checker.ppm"); });
    EXPECT_NE(what.find("checker.ppm: unsupported scene file type '.ppm'"), std::string::npos)
        << what;
}

}  // namespace
}  // namespace igi
