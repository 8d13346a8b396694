// Paths in scene files cannot leave the scene's folder (by "..", an absolute path or a
// symbolic link) unless the caller allows it; bundles refuse names a client must not accept.

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "util/ExpectContains.h"

#include "scene/SceneLoader.h"
#include "scene/TestScenes.h"
#include "scene/TextureLoader.h"

namespace igi {
namespace {

namespace fs = std::filesystem;

using test::kTriangle;
constexpr const char* kLeaves = "leaves the scene's folder; pass --allow-outside-paths to allow it";

// A scene folder ("scene/") next to a folder it must not reach ("outside/"), removed at the
// end of the test.
class PathSafety : public ::testing::Test {
  protected:
    void SetUp() override {
        static std::atomic<int> counter{0};
        root_ = fs::temp_directory_path() /
                ("igi-path-safety-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
        fs::create_directories(root_ / "scene");
        fs::create_directories(root_ / "outside");
        write("outside/tri.obj", kTriangle);
        write("outside/tri.mtl", "newmtl a\nKd 1 1 1\n");
        write("outside/t.ppm", "P3\n1 1\n255\n255 0 0\n");
    }
    void TearDown() override {
        std::error_code ec;
        fs::remove_all(root_, ec);
    }

    fs::path dir() const { return root_ / "scene"; }
    fs::path outside() const { return root_ / "outside"; }

    void write(const std::string& relative, const std::string& text) const {
        std::ofstream(root_ / relative, std::ios::binary) << text;
    }

    // Loads scene/scene.json with `json` as its text; returns the error or "".
    std::string loadError(const std::string& json, bool allow = false) const {
        // A camera, so that a scene with nothing to frame loads too.
        write("scene/scene.json",
              R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},)" + json.substr(1));
        SceneLoadOptions options;
        options.allowOutsidePaths = allow;
        try {
            loadSceneFile(dir() / "scene.json", options);
        } catch (const SceneError& e) {
            return e.what();
        }
        return "";
    }

    fs::path root_;
};

TEST_F(PathSafety, DotDotMeshIsRefusedNamingTheJsonPathUnlessAllowed) {
    const std::string json = R"({"meshes": [{"file": "../outside/tri.obj"}]})";
    const std::string what = loadError(json);
    EXPECT_CONTAINS(
        what, "scene.json: /meshes/0/file: path '../outside/tri.obj' " + std::string(kLeaves));
    EXPECT_EQ(loadError(json, true), "");
}

TEST_F(PathSafety, DotDotInsideAPathIsJudgedByItsNormalForm) {
    fs::create_directories(dir() / "sub");
    EXPECT_CONTAINS(loadError(R"({"meshes": [{"file": "sub/../../outside/tri.obj"}]})"),
                    "path '../outside/tri.obj' " + std::string(kLeaves));
    // Down and back up again stays inside.
    write("scene/tri.obj", kTriangle);
    EXPECT_EQ(loadError(R"({"meshes": [{"file": "sub/../tri.obj"}]})"), "");
}

TEST_F(PathSafety, AbsoluteMeshIsRefusedUnlessAllowed) {
    const std::string file = (outside() / "tri.obj").string();
    const std::string json = R"({"meshes": [{"file": ")" + file + R"("}]})";
    EXPECT_CONTAINS(loadError(json), "/meshes/0/file: path '" + file + "' " + kLeaves);
    EXPECT_EQ(loadError(json, true), "");
}

TEST_F(PathSafety, AllowedAbsolutePathsCannotBeShippedToClients) {
    const std::string file = (outside() / "tri.obj").string();
    write("scene/scene.json", R"({"meshes": [{"file": ")" + file + R"("}]})");
    SceneBundle bundle;
    const std::string what =
        test::sceneErrorOf([&] { loadSceneFile(dir() / "scene.json", &bundle, test::trusted()); });
    EXPECT_CONTAINS(what, file + ": absolute file name: a scene bundle holds paths relative");
}

TEST_F(PathSafety, SymlinkLeadingOutIsRefusedUnlessAllowed) {
    fs::create_symlink(outside() / "tri.obj", dir() / "link.obj");
    const std::string json = R"({"meshes": [{"file": "link.obj"}]})";
    const std::string what = loadError(json);
    EXPECT_CONTAINS(what, "/meshes/0/file: path 'link.obj' leads out of the scene's folder (to '" +
                              fs::weakly_canonical(outside() / "tri.obj").string() +
                              "', through a symbolic link); pass --allow-outside-paths");
    EXPECT_EQ(loadError(json, true), "");
}

TEST_F(PathSafety, SymlinkedFolderLeadingOutIsRefused) {
    fs::create_directory_symlink(outside(), dir() / "assets");
    EXPECT_CONTAINS(loadError(R"({"meshes": [{"file": "assets/tri.obj"}]})"),
                    "path 'assets/tri.obj' leads out of the scene's folder");
}

TEST_F(PathSafety, SymlinkStayingInsideIsFine) {
    write("scene/real.obj", kTriangle);
    fs::create_symlink("real.obj", dir() / "alias.obj");
    EXPECT_EQ(loadError(R"({"meshes": [{"file": "alias.obj"}]})"), "");
}

TEST_F(PathSafety, MtllibLeavingTheFolderNamesTheObjLine) {
    write("scene/m.obj", "mtllib ../outside/tri.mtl\n" + std::string(kTriangle));
    const std::string what = loadError(R"({"meshes": [{"file": "m.obj"}]})");
    EXPECT_CONTAINS(what,
                    "m.obj:1: material library '../outside/tri.mtl': path "
                    "'../outside/tri.mtl' " +
                        std::string(kLeaves));
    EXPECT_EQ(loadError(R"({"meshes": [{"file": "m.obj"}]})", true), "");
}

TEST_F(PathSafety, BareObjIsItsOwnFoldersScene) {
    write("scene/m.obj", "mtllib ../outside/tri.mtl\nusemtl a\n" + std::string(kTriangle));
    const std::string what = test::sceneErrorOf([&] { loadSceneFile(dir() / "m.obj"); });
    EXPECT_CONTAINS(what, "m.obj:1: material library '../outside/tri.mtl': path");
    EXPECT_CONTAINS(what, kLeaves);
    const Scene s = loadSceneFile(dir() / "m.obj", test::trusted());
    ASSERT_EQ(s.materials.size(), 1u);
    EXPECT_EQ(s.materials[0].name, "a");
}

TEST_F(PathSafety, MapKdLeavingTheFolderNamesTheMtlLine) {
    write("scene/m.obj", "mtllib m.mtl\nusemtl a\n" + std::string(kTriangle));
    write("scene/m.mtl", "newmtl a\nKd 1 1 1\nmap_Kd ../outside/t.ppm\n");
    const std::string json = R"({"meshes": [{"file": "m.obj"}]})";
    EXPECT_CONTAINS(loadError(json), "m.mtl:3: path '../outside/t.ppm' " + std::string(kLeaves));
    EXPECT_EQ(loadError(json, true), "");
}

TEST_F(PathSafety, OverrideTextureLeavingTheFolderNamesTheJsonPath) {
    write("scene/m.obj", "mtllib m.mtl\nusemtl a\n" + std::string(kTriangle));
    write("scene/m.mtl", "newmtl a\nKd 1 1 1\n");
    const std::string json = R"({"meshes": [{"file": "m.obj"}],
                                 "materials": {"a": {"texture": "../outside/t.ppm"}}})";
    EXPECT_CONTAINS(loadError(json),
                    "/materials/a/texture: path '../outside/t.ppm' " + std::string(kLeaves));
    EXPECT_EQ(loadError(json, true), "");
}

TEST_F(PathSafety, GltfBufferAndImageUrisLeavingTheFolderAreRefused) {
    // The bytes do not matter: the URI is refused before anything is read.
    write("outside/t.bin", std::string(36, '\0'));
    write("scene/buffer.gltf", R"({"asset": {"version": "2.0"},
        "buffers": [{"byteLength": 36, "uri": "..%2Foutside/t.bin"}]})");
    EXPECT_CONTAINS(loadError(R"({"meshes": [{"file": "buffer.gltf"}]})"),
                    "buffer.gltf: /buffers/0/uri: path '../outside/t.bin' " + std::string(kLeaves));
    EXPECT_EQ(loadError(R"({"meshes": [{"file": "buffer.gltf"}]})", true), "");

    write("scene/image.gltf", R"({"asset": {"version": "2.0"},
        "images": [{"uri": "../outside/t.ppm"}]})");
    EXPECT_CONTAINS(loadError(R"({"meshes": [{"file": "image.gltf"}]})"),
                    "image.gltf: /images/0/uri: path '../outside/t.ppm' " + std::string(kLeaves));
}

TEST_F(PathSafety, NulInAPathIsAlwaysRefused) {
    const std::string what = loadError(R"({"meshes": [{"file": "sub/x\u0000.obj"}]})", true);
    EXPECT_CONTAINS(what, "path contains a NUL byte");
}

TEST(DiskFileSource, RefusesEscapingPathsInEveryCall) {
    DiskFileSource disk(test::testdataDir() / "gltf");
    for (const std::string path : {"../minimal/box.mtl", "/etc/passwd", "a/../../x"}) {
        SCOPED_TRACE(path);
        EXPECT_CONTAINS(test::sceneErrorOf([&] { disk.read(path); }), kLeaves);
        EXPECT_CONTAINS(test::sceneErrorOf([&] { disk.exists(path); }), kLeaves);
    }
    EXPECT_CONTAINS(test::sceneErrorOf([&] { disk.list(".."); }), kLeaves);
    EXPECT_TRUE(disk.filesRead().empty());
    EXPECT_TRUE(disk.exists("triangle.gltf"));
}

TEST(DiskFileSource, CaseInsensitiveLookupInsideTheFolderIsAllowed) {
    DiskFileSource disk(test::testdataDir() / "minimal");
    EXPECT_EQ(disk.list(""),
              (std::vector<std::string>{"box.mtl", "box.obj", "checker.ppm", "scene.json"}));
    EXPECT_EQ(locateFile(disk, "CHECKER.PPM"), std::optional<std::string>("checker.ppm"));
}

TEST(SceneBundle, ClientsRefuseAbsoluteEmptyAndNulNames) {
    SceneBundle bundle;
    bundle.sceneName = "scene.json";
    bundle.sceneText = R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]}})";
    bundle.files = {{"/etc/passwd", "x"}};
    EXPECT_CONTAINS(test::sceneErrorOf([&] { loadSceneBundle(bundle); }),
                    "/etc/passwd: absolute file name");
    bundle.files = {{std::string("a.obj\0b", 7), "x"}};
    EXPECT_CONTAINS(test::sceneErrorOf([&] { loadSceneBundle(bundle); }),
                    "a.obj\\0b: file name in the scene bundle contains a NUL byte");
    bundle.files = {{"", "x"}};
    EXPECT_CONTAINS(test::sceneErrorOf([&] { loadSceneBundle(bundle); }), "empty name");
    // "../" keys are what a master allowed outside paths sends: accepted.
    bundle.files = {{"../shared/x.obj", "x"}};
    EXPECT_NO_THROW(loadSceneBundle(bundle));
}

}  // namespace
}  // namespace igi
