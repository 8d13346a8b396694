// Instances end to end (issue 36, item 3): an OBJ file named twice by a scene file is one
// geometry placed twice; the image is the same whichever client rendered which tile, while one
// of the two moves, and it is the image of the two copies flattened, up to rounding.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <tuple>

#include <gtest/gtest.h>

#include "Process.h"
#include "Session.h"
#include "image/ImageCompare.h"
#include "image/ImageIO.h"

namespace igi {
namespace {

using namespace igi::testing;
namespace fs = std::filesystem;

// The Cornell room with two balls of scenes/cornell/sphere.obj, the second from `secondFile`
// (sphere.obj again: an instance; a copy of it: a mesh of its own), and an animation that
// moves the second ball at frame 2.
void writeScene(const fs::path& dir, const std::string& secondFile) {
    const fs::path cornell = sourceDir() / "scenes/cornell";
    for (const char* f : {"room.obj", "room.mtl", "sphere.obj", "sphere.mtl"})
        fs::copy_file(cornell / f, dir / f, fs::copy_options::overwrite_existing);
    fs::copy_file(cornell / "sphere.obj", dir / "copy.obj", fs::copy_options::overwrite_existing);
    std::ofstream(dir / "scene.json") << R"({
  "camera": {"position": [0, 1, 3.35], "look_at": [0, 1, 0], "up": [0, 1, 0], "fov_y": 40},
  "meshes": [
    {"file": "room.obj", "name": "room"},
    {"file": "sphere.obj", "name": "ball_a", "transform": {"translate": [-0.45, 0.3, 0], "scale": 0.3}},
    {"file": ")" + secondFile + R"(", "name": "ball_b",
     "transform": {"translate": [0.45, 0.3, 0.2], "rotate_deg": [0, 30, 10], "scale": [0.3, 0.4, 0.25]}}
  ],
  "lights": [{"type": "quad", "name": "ceiling_light", "corner": [-0.25, 1.98, -0.2],
              "edge1": [0.5, 0, 0], "edge2": [0, 0, 0.4], "radiance": [17, 13.5, 9]}],
  "render": {"interleave": [3, 3], "direct_samples": 4, "indirect_vpls": 18, "caustic_photons": 500}
})";
    std::ofstream(dir / "move.anim.json") << R"({"objects": {"ball_b": [
  {"frame": 1, "translate": [0.45, 0.3, 0.2]},
  {"frame": 2, "translate": [0.3, 0.7, -0.1]}]}})";
}

ProcessResult render(const fs::path& dir, const std::string& name, int clients, bool animate) {
    std::vector<std::string> command = {(binDir() / "igi-master").string(),
                                        "--scene",
                                        (dir / "scene.json").string(),
                                        "--width",
                                        "96",
                                        "--height",
                                        "72",
                                        "--frames",
                                        "4",
                                        "--listen",
                                        "127.0.0.1:0",
                                        "--local-clients",
                                        std::to_string(clients),
                                        "--output",
                                        (dir / (name + ".exr")).string()};
    if (animate) command.insert(command.end(), {"--animation", (dir / "move.anim.json").string()});
    return runProcess(command, dir / (name + ".log"), 300);
}

TEST(Instances, ThreeClientsRenderAnObjNamedTwiceAsOneDoesWhileOneInstanceMoves) {
    const fs::path dir = scratchDir("instances");
    writeScene(dir, "sphere.obj");
    for (const auto& [name, clients, animate] :
         {std::tuple{"three", 3, true}, {"one", 1, true}, {"still", 1, false}}) {
        const ProcessResult r = render(dir, name, clients, animate);
        ASSERT_EQ(r.exitCode, 0) << r.output;
    }
    expectSameImage(dir / "three.exr", dir / "one.exr");
    // The move shows: the animated image is not the still one.
    const Image moved = readFiniteImage(dir / "one.exr"),
                still = readFiniteImage(dir / "still.exr");
    EXPECT_GT(compareImages(moved, still).relativeMse, 1e-3);
    fs::remove_all(dir);
}

// The instanced ball renders as a copy of its file does (a mesh of its own, in world space),
// up to the rounding of its transform: applied to each ray instead of to each vertex.
TEST(Instances, AnInstanceRendersAsAFlattenedCopy) {
    const fs::path dir = scratchDir("instances-flat");
    writeScene(dir, "sphere.obj");
    const ProcessResult a = render(dir, "instanced", 1, true);
    ASSERT_EQ(a.exitCode, 0) << a.output;
    writeScene(dir, "copy.obj");
    const ProcessResult b = render(dir, "flattened", 1, true);
    ASSERT_EQ(b.exitCode, 0) << b.output;
    const ImageDifference d = compareImages(readFiniteImage(dir / "instanced.exr"),
                                            readFiniteImage(dir / "flattened.exr"));
    std::printf("instanced against flattened: relMSE %.3g\n", d.relativeMse);
    EXPECT_LT(d.relativeMse, 1e-6);  // 5e-12 measured
    fs::remove_all(dir);
}

}  // namespace
}  // namespace igi
