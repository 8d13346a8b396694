// The whole system as users run it: a master and client processes on loopback, images read
// back from disk.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "Process.h"
#include "Session.h"
#include "image/ImageIO.h"
#include "math/Color.h"

namespace igi {
namespace {

using namespace igi::testing;
namespace fs = std::filesystem;

ProcessResult runMaster(const fs::path& dir, const std::string& name, std::vector<std::string> args,
                        double timeout = 300) {
    std::vector<std::string> command = {(binDir() / "igi-master").string()};
    command.insert(command.end(), args.begin(), args.end());
    return runProcess(command, dir / (name + ".log"), timeout);
}

void expectFinite(const Image& image, const std::string& what) {
    for (const auto& p : image.pixels)
        ASSERT_TRUE(isFinite(p)) << what << " has a NaN or infinite pixel";
}

// Renders `scene` at w x h for `frames` frames with 3 local clients and with 1 and expects the
// same bits; `three` receives the 3-client image (finite), `extra3` adds flags to that run.
void renderWithThreeAndOneClients(const fs::path& dir, const std::string& scene, int w, int h,
                                  int frames, Image& three,
                                  const std::vector<std::string>& extra3 = {}) {
    const std::vector<std::string> common = {"--scene",  scene,
                                             "--width",  std::to_string(w),
                                             "--height", std::to_string(h),
                                             "--frames", std::to_string(frames),
                                             "--listen", "127.0.0.1:0"};
    auto args3 = common, args1 = common;
    args3.insert(args3.end(), {"--local-clients", "3", "--output", (dir / "three.exr").string()});
    args3.insert(args3.end(), extra3.begin(), extra3.end());
    args1.insert(args1.end(), {"--local-clients", "1", "--output", (dir / "one.exr").string()});
    const ProcessResult r3 = runMaster(dir, "three", args3), r1 = runMaster(dir, "one", args1);
    ASSERT_EQ(r3.exitCode, 0) << r3.output;
    ASSERT_EQ(r1.exitCode, 0) << r1.output;
    three = readImage(dir / "three.exr");
    const Image one = readImage(dir / "one.exr");
    ASSERT_EQ(three.width, w);
    ASSERT_EQ(three.height, h);
    expectFinite(three, "three.exr");
    for (std::size_t i = 0; i < three.pixels.size(); ++i)
        ASSERT_EQ(three.pixels[i], one.pixels[i])
            << "pixel " << i % std::size_t(w) << "," << i / std::size_t(w) << " differs";
}

TEST(EndToEnd, TwoClientsRenderTheDefaultSceneExactlyAsOneDoes) {
    const fs::path dir = scratchDir("default");
    const std::string scene = (sourceDir() / "scenes/cornell/cornell.json").string();
    const std::vector<std::string> common = {"--scene",  scene,        "--width",  "160",
                                             "--height", "120",        "--frames", "3",
                                             "--listen", "127.0.0.1:0"};
    auto args2 = common;
    args2.insert(args2.end(),
                 {"--local-clients", "2", "--output", (dir / "two.exr").string(), "--output",
                  (dir / "two.png").string(), "--stats-json", (dir / "two.json").string()});
    auto args1 = common;
    args1.insert(args1.end(), {"--local-clients", "1", "--output", (dir / "one.exr").string()});
    const ProcessResult two = runMaster(dir, "two", args2), one = runMaster(dir, "one", args1);
    ASSERT_EQ(two.exitCode, 0) << two.output;
    ASSERT_EQ(one.exitCode, 0) << one.output;

    const Image a = readImage(dir / "two.exr"), b = readImage(dir / "one.exr");
    ASSERT_EQ(a.width, 160);
    ASSERT_EQ(a.height, 120);
    expectFinite(a, "two.exr");
    expectFinite(b, "one.exr");

    // The PNG is the same image, tone-mapped.
    const Image png = readImage(dir / "two.png");
    ASSERT_EQ(png.width, 160);
    expectFinite(png, "two.png");

    // The light is the brightest thing in view: the top middle of the image.
    std::size_t brightest = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
        if (luminance(a.pixels[i]) > luminance(a.pixels[brightest])) brightest = i;
    const int bx = int(brightest % 160), by = int(brightest / 160);
    EXPECT_LT(by, 20) << "brightest pixel at " << bx << "," << by;
    EXPECT_NEAR(bx, 80, 20) << "brightest pixel at " << bx << "," << by;
    // Walls are lit: the left wall is red, the right wall green.
    const glm::vec3 left = a.at(20, 60), right = a.at(140, 60);
    EXPECT_GT(left.x, 2 * left.y);
    EXPECT_GT(right.y, 2 * right.x);

    // Statistics: every frame, every pixel, both clients at work.
    std::ifstream statsFile(dir / "two.json");
    const auto stats = nlohmann::json::parse(statsFile);
    ASSERT_EQ(stats["frames"].size(), 3u);
    std::uint64_t tiles = 0;
    for (const auto& f : stats["frames"]) {
        EXPECT_EQ(f["pixels"], 160 * 120);
        EXPECT_GT(f["rays"].get<std::uint64_t>(), 0u);
        EXPECT_GT(f["wire_bytes"].get<std::uint64_t>(), 0u);
        EXPECT_GT(f["seconds"].get<double>(), 0.0);
        EXPECT_GT(f["vpls"].get<double>(), 4.0);
        EXPECT_GT(f["caustic_photons"].get<double>(),
                  0.0);  // the scene has a glass ball and a mirror
        EXPECT_GT(f["shadow_rays"].get<std::uint64_t>(), 0u);
        tiles += f["tiles"].get<std::uint64_t>();
    }
    ASSERT_EQ(stats["clients"].size(), 2u);
    std::uint64_t clientTiles = 0;
    for (const auto& c : stats["clients"]) {
        EXPECT_GT(c["tiles"].get<std::uint64_t>(), 0u) << "a client did nothing";
        clientTiles += c["tiles"].get<std::uint64_t>();
    }
    EXPECT_EQ(clientTiles, tiles);
    EXPECT_GT(stats["fps"].get<double>(), 0.0);
    fs::remove_all(dir);
}

// The Cornell box open to a sun behind the camera, with a spot light inside: directional light
// (direct, VPLs from the disk, caustic photons through the glass ball) and the spot's cone.
TEST(EndToEnd, ThreeClientsRenderASunAndSpotLitSceneExactlyAsOneDoes) {
    const fs::path dir = scratchDir("sunlit");
    const std::string scene = (sourceDir() / "scenes/cornell/sunlit.json").string();
    Image a;
    renderWithThreeAndOneClients(dir, scene, 120, 90, 3, a);
    if (HasFatalFailure()) return;
    // The sun comes in from behind the camera, to the right and above: the back wall is lit
    // on its right, and the mirror box (left) casts a shadow on its left.
    double lit = 0;
    for (const glm::vec3& p : a.pixels) lit += luminance(p);
    EXPECT_GT(lit / double(a.pixels.size()), 0.05);
}

// Objects on a floor under an HDR map and a sun: the map travels to the clients with the scene,
// the camera sees it above the floor, and every client lights with it alike.
TEST(EndToEnd, ThreeClientsRenderASceneUnderAnEnvironmentMapExactlyAsOneDoes) {
    const fs::path dir = scratchDir("sky");
    const std::string scene = (sourceDir() / "scenes/sky/sky.json").string();
    Image a;
    renderWithThreeAndOneClients(dir, scene, 120, 90, 3, a);
    if (HasFatalFailure()) return;
    // The top rows see the studio's backdrop, which is neither black nor one flat colour.
    const glm::vec3 left = a.at(2, 2), right = a.at(117, 2);
    EXPECT_GT(luminance(left), 0.01f);
    EXPECT_NE(left, right);
}

// With many lights each point chooses its light samples (the light tree) and its VPLs (by
// importance, from a pool per set) for itself: still a function of the pixel, the frame and the
// set only, so the image does not depend on which client rendered which tile.
TEST(EndToEnd, ThreeClientsRenderAManyLightSceneExactlyAsOneDoes) {
    const fs::path dir = scratchDir("many-lights");
    const std::string scene = (sourceDir() / "scenes/interior/glossy.json").string();
    Image a;
    renderWithThreeAndOneClients(dir, scene, 120, 90, 3, a,
                                 {"--stats-json", (dir / "three.json").string()});
    if (HasFatalFailure()) return;
    std::ifstream statsFile(dir / "three.json");
    const auto stats = nlohmann::json::parse(statsFile);
    // The sets hold a pool (8 x 18 VPLs by default), of which each point connects to 18 at most
    // (a glossy point's continuation reaches a second point, which connects to 18 more).
    EXPECT_GT(stats["frames"][1]["vpls"].get<double>(), 100.0);
    EXPECT_LT(stats["frames"][1]["shadow_rays_per_pixel"].get<double>(), 60.0);
    int busy = 0;
    for (const auto& c : stats["clients"]) busy += c["tiles"].get<std::uint64_t>() > 0;
    EXPECT_EQ(busy, 3);
    fs::remove_all(dir);
}

// glTF metallic-roughness (GGX) lobes sample with each pixel's own numbers and VPLs carry their
// lobe: the image of Khronos' 7 x 7 grid of metal and dielectric spheres, smooth to rough, does
// not depend on which client rendered which tile, first frame and accumulated ones alike.
TEST(EndToEnd, ThreeClientsRenderMetallicRoughnessSpheresExactlyAsOneDoes) {
    const fs::path gltf = sourceDir() /
                          "../shared/scenes/gltf/MetalRoughSpheresNoTextures/glTF/"
                          "MetalRoughSpheresNoTextures.gltf";
    if (!fs::exists(gltf)) GTEST_SKIP() << gltf << " is not here";
    const fs::path dir = scratchDir("metal-rough");
    Image a;
    renderWithThreeAndOneClients(dir, gltf.string(), 96, 72, 4, a);
    if (HasFatalFailure()) return;
    double sum = 0;
    for (const glm::vec3& p : a.pixels) sum += luminance(p);
    EXPECT_GT(sum / double(a.pixels.size()), 0.01);
    fs::remove_all(dir);
}

// Alpha cut-outs (MASK at three cut-offs) and BLEND's stochastic coverage are decided by Embree
// filter functions from the ray alone: Khronos' AlphaBlendModeTest renders the same whichever
// client rendered which tile, in packets or single rays.
TEST(EndToEnd, ThreeClientsRenderAlphaBlendModeTestExactlyAsOneDoes) {
    const fs::path gltf =
        sourceDir() / "../shared/scenes/gltf/AlphaBlendModeTest/glTF/AlphaBlendModeTest.gltf";
    if (!fs::exists(gltf)) GTEST_SKIP() << gltf << " is not here";
    const fs::path dir = scratchDir("alpha");
    Image a;
    renderWithThreeAndOneClients(dir, gltf.string(), 96, 72, 3, a);
    if (HasFatalFailure()) return;
    fs::remove_all(dir);
}

// The files of a scene with an emissive-textured glTF screen (a bright and a dark half) whose
// second primitive has vertex colours (COLOR_0, normalized bytes), over a floor with an MTL
// height map (bump -bm): the issue 34 features in one scene, written into `dir`.
void writeTexturedScene(const fs::path& dir) {
    auto ppm = [](int w, int h, const std::vector<unsigned char>& rgb) {
        std::string s = "P6\n" + std::to_string(w) + " " + std::to_string(h) + "\n255\n";
        s.append(rgb.begin(), rgb.end());
        return s;
    };
    std::vector<unsigned char> heights;
    for (int i = 0; i < 16 * 16; ++i) {
        const unsigned char v = (i % 16 / 4 + i / 16 / 4) % 2 ? 200 : 40;  // 4 x 4 texel checks
        heights.insert(heights.end(), {v, v, v});
    }
    std::ofstream(dir / "h.ppm", std::ios::binary) << ppm(16, 16, heights);
    std::ofstream(dir / "e.ppm", std::ios::binary)
        << ppm(4, 1, {255, 255, 255, 255, 255, 255, 0, 0, 0, 0, 0, 0});
    std::ofstream(dir / "floor.mtl") << "newmtl stone\nKd 0.7 0.7 0.7\nbump -bm 4 h.ppm\n";
    std::ofstream(dir / "floor.obj")
        << "mtllib floor.mtl\nv -3 0 -3\nv -3 0 3\nv 3 0 3\nv 3 0 -3\n"
           "vt 0 0\nvt 0 2\nvt 2 2\nvt 2 0\nusemtl stone\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
    // Screen: y = 1.5, facing down; panel: the back wall z = -1.5, facing +z.
    const std::vector<float> positions = {-1, 1.5f,  -1,   1, 1.5f,  -1, 1,     1.5f,
                                          1,  -1,    1.5f, 1, -2,    0,  -1.5f, 2,
                                          0,  -1.5f, 2,    2, -1.5f, -2, 2,     -1.5f};
    const std::vector<float> uvs = {0, 0, 1, 0, 1, 1, 0, 1, 0, 0, 1, 0, 1, 1, 0, 1};
    const std::vector<unsigned char> colours = {255, 40, 40,  255, 40,  40, 255, 255,
                                                40,  40, 255, 255, 255, 40, 40,  255};
    const std::vector<std::uint16_t> indices = {0, 1, 2, 0, 2, 3, 0, 1, 2, 0, 2, 3};
    std::string bin(reinterpret_cast<const char*>(positions.data()), positions.size() * 4);
    bin.append(reinterpret_cast<const char*>(uvs.data()), uvs.size() * 4);
    bin.append(reinterpret_cast<const char*>(colours.data()), colours.size());
    bin.append(reinterpret_cast<const char*>(indices.data()), indices.size() * 2);
    std::ofstream(dir / "screen.bin", std::ios::binary) << bin;
    using nlohmann::json;
    const json gltf = {
        {"asset", {{"version", "2.0"}}},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"mesh", 0}}}},
        {"meshes",
         {{{"primitives",
            {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}},
              {"indices", 3},
              {"material", 0}},
             {{"attributes", {{"POSITION", 4}, {"TEXCOORD_0", 5}, {"COLOR_0", 2}}},
              {"indices", 6},
              {"material", 1}}}}}}},
        {"materials",
         {{{"name", "screen"},
           {"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 0, 1}}}},
           {"emissiveFactor", {1, 1, 1}},
           {"emissiveTexture", {{"index", 0}}},
           {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 6}}}}}},
          {{"name", "panel"}, {"pbrMetallicRoughness", {{"metallicFactor", 0}}}}}},
        {"extensionsUsed", {"KHR_materials_emissive_strength"}},
        {"textures", {{{"source", 0}}}},
        {"images", {{{"uri", "e.ppm"}}}},
        {"buffers", {{{"uri", "screen.bin"}, {"byteLength", bin.size()}}}},
        {"bufferViews",
         {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
          {{"buffer", 0}, {"byteOffset", 96}, {"byteLength", 32}},
          {{"buffer", 0}, {"byteOffset", 160}, {"byteLength", 16}},
          {{"buffer", 0}, {"byteOffset", 176}, {"byteLength", 12}},
          {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 48}},
          {{"buffer", 0}, {"byteOffset", 128}, {"byteLength", 32}},
          {{"buffer", 0}, {"byteOffset", 188}, {"byteLength", 12}}}},
        {"accessors",
         {{{"bufferView", 0},
           {"componentType", 5126},
           {"count", 4},
           {"type", "VEC3"},
           {"min", {-1, 1.5, -1}},
           {"max", {1, 1.5, 1}}},
          {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
          {{"bufferView", 2},
           {"componentType", 5121},
           {"normalized", true},
           {"count", 4},
           {"type", "VEC4"}},
          {{"bufferView", 3}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}},
          {{"bufferView", 4},
           {"componentType", 5126},
           {"count", 4},
           {"type", "VEC3"},
           {"min", {-2, 0, -1.5}},
           {"max", {2, 2, -1.5}}},
          {{"bufferView", 5}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
          {{"bufferView", 6}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}}};
    std::ofstream(dir / "screen.gltf") << gltf.dump();
    std::ofstream(dir / "scene.json")
        << R"({"meshes": [{"file": "floor.obj"}, {"file": "screen.gltf"}],
               "camera": {"position": [0, 0.8, 4], "look_at": [0, 0.6, 0], "fov_y": 50}})";
}

// Emissive textures (light sampling by the texels' power, light paths from the texels), vertex
// colours and bump maps are functions of the hit and the light sample alone: the image does not
// depend on which client rendered which tile.
TEST(EndToEnd, ThreeClientsRenderEmissiveTexturesColoursAndBumpsExactlyAsOneDoes) {
    const fs::path dir = scratchDir("textured");
    writeTexturedScene(dir);
    Image a;
    renderWithThreeAndOneClients(dir, (dir / "scene.json").string(), 96, 72, 3, a);
    if (HasFatalFailure()) return;
    // The screen's left half (world -x) is bright: the floor is lit more on the left.
    double left = 0, right = 0;
    for (int y = 44; y < 56; ++y)
        for (int x = 10; x < 40; ++x) {
            left += luminance(a.at(x, y));
            right += luminance(a.at(95 - x, y));
        }
    EXPECT_GT(left, 1.3 * right);
    fs::remove_all(dir);
}

TEST(EndToEnd, ABadSceneFileIsAClearErrorAndANonZeroExit) {
    const fs::path dir = scratchDir("bad");
    std::ofstream(dir / "bad.json")
        << "{\n  \"camera\": {\"position\": [0, 1, 3], \"look_at\": [0, 1, 0],\n"
           "             \"up\": [0, 1, 0], \"fov_y\": 40, \"zoom\": 2},\n"
           "  \"meshes\": []\n}\n";
    const ProcessResult r =
        runMaster(dir, "bad", {"--scene", (dir / "bad.json").string(), "--local-clients", "1"}, 60);
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("bad.json"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("/camera/zoom"), std::string::npos) << r.output;

    std::ofstream(dir / "missing.json") << "{\"meshes\": [{\"file\": \"nowhere.obj\"}]}";
    const ProcessResult m = runMaster(
        dir, "missing", {"--scene", (dir / "missing.json").string(), "--local-clients", "1"}, 60);
    EXPECT_NE(m.exitCode, 0);
    EXPECT_NE(m.output.find("nowhere.obj"), std::string::npos) << m.output;
    fs::remove_all(dir);
}

TEST(EndToEnd, AScenePathOutsideTheScenesFolderNeedsAllowOutsidePaths) {
    const fs::path dir = scratchDir("outside");
    fs::create_directories(dir / "scene");
    std::ofstream(dir / "floor.obj") << "v -1 0 -1\nv 1 0 -1\nv 0 0 1\nf 1 3 2\n";
    std::ofstream(dir / "scene" / "s.json")
        << R"({"camera": {"position": [0, 2, 3], "look_at": [0, 0, 0], "up": [0, 1, 0],
                          "fov_y": 45},
              "image": {"width": 16, "height": 16},
              "meshes": [{"file": "../floor.obj"}],
              "lights": [{"type": "point", "position": [0, 1, 0], "intensity": [1, 1, 1]}]})";
    const std::vector<std::string> args = {
        "--scene",  (dir / "scene" / "s.json").string(), "--local-clients", "1", "--frames", "1",
        "--output", (dir / "out.exr").string()};
    const ProcessResult refused = runMaster(dir, "refused", args, 60);
    EXPECT_NE(refused.exitCode, 0);
    EXPECT_NE(refused.output.find("leaves the scene's folder"), std::string::npos)
        << refused.output;
    EXPECT_FALSE(fs::exists(dir / "out.exr"));

    auto allowed = args;
    allowed.push_back("--allow-outside-paths");
    const ProcessResult r = runMaster(dir, "allowed", allowed, 120);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    expectFinite(readImage(dir / "out.exr"), "out.exr");
    fs::remove_all(dir);
}

TEST(EndToEnd, ABareObjFromAnotherFolderRendersWithoutASharedDisk) {
    // The clients get every byte from the master; the OBJ's MTL is found next to it.
    const fs::path obj = sourceDir() / "../shared/scenes/cornell-box/CornellBox-Original.obj";
    if (!fs::exists(obj)) GTEST_SKIP() << obj << " is not here";
    const fs::path dir = scratchDir("bareobj");
    const ProcessResult r =
        runMaster(dir, "obj",
                  {"--scene", obj.string(), "--local-clients", "1", "--width", "64", "--height",
                   "64", "--output", (dir / "box.exr").string()});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const Image image = readImage(dir / "box.exr");
    expectFinite(image, "box.exr");
    double sum = 0;
    for (const auto& p : image.pixels) sum += luminance(p);
    EXPECT_GT(sum / double(image.pixels.size()), 0.01);  // lit by its own emissive light
    fs::remove_all(dir);
}

}  // namespace
}  // namespace igi

namespace igi {
namespace {

// Issue 40: an unknown --log-level silenced every message, errors included; --seed went
// through a double and refused 2^63 .. 2^64 - 1 with a wrong message.
TEST(CommandLine, LogLevelsAreCheckedAndSeedsAreWholeSixtyFourBitNumbers) {
    const fs::path dir = scratchDir("command-line");
    auto args = sceneArgs(1);
    args.resize(args.size() - 2);  // its --log-level info: each run below gives its own
    args.insert(args.end(), {"--local-clients", "1"});
    auto badLevel = args;
    badLevel.insert(badLevel.end(), {"--log-level", "verbose"});
    const ProcessResult level = runProcess(masterCommand(badLevel), dir / "level.log");
    EXPECT_NE(level.exitCode, 0);
    EXPECT_NE(level.output.find("--log-level"), std::string::npos) << level.output;
    EXPECT_NE(level.output.find("verbose"), std::string::npos) << level.output;
    EXPECT_EQ(level.output.find("At Most 1"), std::string::npos) << level.output;
    const ProcessResult client =
        runProcess(clientCommand({"--log-level", "debugg"}), dir / "client.log");
    EXPECT_NE(client.exitCode, 0);
    EXPECT_NE(client.output.find("--log-level"), std::string::npos) << client.output;

    auto upper = args;
    upper.insert(upper.end(), {"--log-level", "WARN", "--seed", "18446744073709551615", "--output",
                               (dir / "max.exr").string()});
    const ProcessResult max = runProcess(masterCommand(upper), dir / "max.log");
    ASSERT_EQ(max.exitCode, 0) << max.output;
    EXPECT_EQ(max.output.find("[info]"), std::string::npos) << "WARN hides info lines";
    auto below = args;
    below.insert(below.end(),
                 {"--seed", "18446744073709551614", "--output", (dir / "below.exr").string()});
    ASSERT_EQ(runProcess(masterCommand(below), dir / "below.log").exitCode, 0);
    // Seeds that differ in their lowest bit, above 2^53, give different images.
    const Image a = readImage(dir / "max.exr"), b = readImage(dir / "below.exr");
    EXPECT_NE(a.pixels, b.pixels);
    for (const char* bad : {"-1", "18446744073709551616", "1e30", "12x"}) {
        auto wrong = args;
        wrong.insert(wrong.end(), {"--seed", bad});
        const ProcessResult r = runProcess(masterCommand(wrong), dir / "bad-seed.log");
        EXPECT_NE(r.exitCode, 0) << bad;
        EXPECT_NE(r.output.find("expected a whole number from 0 to 18446744073709551615"),
                  std::string::npos)
            << r.output;
    }
}

}  // namespace
}  // namespace igi
