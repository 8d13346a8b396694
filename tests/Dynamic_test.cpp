// Dynamic scenes end to end: objects moved by an animation or by control commands, frame by
// frame, with real processes; every frame's image read back from disk.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "Session.h"
#include "image/ImageIO.h"
#include "math/Color.h"

namespace igi {
namespace {

using namespace igi::testing;
namespace fs = std::filesystem;

// tests/data/dynamic/scene.json looks straight down from y = 6 with a 36 degree field of view
// at a 96 x 96 image: world (x, z) on a plane at height h is at pixel (px, py) below.
constexpr int kSize = 96;
const float kHalf = 6.0f * std::tan(18.0f * 3.14159265f / 180.0f);
int pixelOf(float world, float height = 0) {
    return int(std::lround((world * 6.0f / (6.0f - height) / kHalf + 1.0f) * 0.5f * kSize - 0.5f));
}

fs::path dynamicScene(const std::string& file) {
    return sourceDir() / "tests/data/dynamic" / file;
}

/// Renders the dynamic scene with an animation into `dir`/frame_NN.exr; returns the stats.
nlohmann::json renderSequence(const fs::path& dir, const std::string& animation, int frames,
                              bool accumulate, int clients = 2) {
    std::vector<std::string> args = {(binDir() / "igi-master").string(),
                                     "--scene",
                                     dynamicScene("scene.json").string(),
                                     "--frames",
                                     std::to_string(frames),
                                     "--local-clients",
                                     std::to_string(clients),
                                     "--listen",
                                     "127.0.0.1:0",
                                     "--output-sequence",
                                     (dir / "frame_%02d.exr").string(),
                                     "--stats-json",
                                     (dir / "stats.json").string()};
    if (!animation.empty())
        args.insert(args.end(), {"--animation", dynamicScene(animation).string()});
    if (!accumulate) args.push_back("--no-accumulate");
    const ProcessResult r = runProcess(args, dir / "master.log");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    std::ifstream in(dir / "stats.json");
    return nlohmann::json::parse(in);
}

Image frameImage(const fs::path& dir, int frame) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%02d.exr", frame);
    return readFiniteImage(dir / name);
}

/// Fraction of red pixels (the box) in a square window around (px, py).
double redFraction(const Image& image, int px, int py, int radius) {
    int red = 0, total = 0;
    for (int y = py - radius; y <= py + radius; ++y)
        for (int x = px - radius; x <= px + radius; ++x) {
            const glm::vec3 c = image.at(x, y);
            red += c.x > 3.0f * c.y + 1e-4f;
            ++total;
        }
    return double(red) / total;
}

/// Mean absolute difference between two frames over the columns [x0, x1).
double meanAbsoluteDifference(const Image& a, const Image& b, int x0 = 0, int x1 = kSize) {
    double sum = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = x0; x < x1; ++x)
            sum += std::fabs(luminance(a.at(x, y)) - luminance(b.at(x, y)));
    return sum / (double(a.height) * (x1 - x0));
}

const int kBoxRow = pixelOf(0.0f);
const int kLeftBox = pixelOf(-0.8f, 0.6f), kRightBox = pixelOf(0.8f, 0.6f);

TEST(Dynamic, AMovedObjectAndItsShadowAreAtTheirNewPlaceInTheNextFrame) {
    const fs::path dir = scratchDir("moved");
    const auto stats = renderSequence(dir, "jump.json", 4, false);
    const Image before = frameImage(dir, 1), after = frameImage(dir, 2);
    EXPECT_GT(redFraction(before, kLeftBox, kBoxRow, 2), 0.9);
    EXPECT_EQ(redFraction(before, kRightBox, kBoxRow, 2), 0.0);
    EXPECT_EQ(redFraction(after, kLeftBox, kBoxRow, 2), 0.0);
    EXPECT_GT(redFraction(after, kRightBox, kBoxRow, 2), 0.9);
    // The point light above the middle throws each box's shadow outward, onto x = -1.15 or +1.15.
    const int leftShadow = pixelOf(-1.15f), rightShadow = pixelOf(1.15f);
    auto lum = [&](const Image& im, int x) { return luminance(im.at(x, kBoxRow)); };
    EXPECT_LT(lum(before, leftShadow), 0.5f * lum(after, leftShadow));
    EXPECT_LT(lum(after, rightShadow), 0.5f * lum(before, rightShadow));
    EXPECT_EQ(stats["frames"][1]["epoch"], 0);
    EXPECT_EQ(stats["frames"][2]["epoch"], 1);
    fs::remove_all(dir);
}

TEST(Dynamic, AFrameNeverMixesTilesOfTwoEpochs) {
    // The box jumps every frame; two frames are always in flight on two clients. A frame made of
    // tiles of two epochs would show parts of the box at both places.
    const fs::path dir = scratchDir("epochs");
    const auto stats = renderSequence(dir, "alternate.json", 12, false);
    for (int f = 0; f < 12; ++f) {
        const Image image = frameImage(dir, f);
        const bool left = f % 2 == 0;
        EXPECT_GT(redFraction(image, left ? kLeftBox : kRightBox, kBoxRow, 3), 0.6)
            << "frame " << f;
        EXPECT_EQ(redFraction(image, left ? kRightBox : kLeftBox, kBoxRow, 6), 0.0)
            << "frame " << f;
        EXPECT_EQ(stats["frames"][std::size_t(f)]["epoch"], f) << "frame " << f;
    }
    fs::remove_all(dir);
}

TEST(Dynamic, AccumulationRestartsOnAChangeAndConvergesAgain) {
    const fs::path dir = scratchDir("accumulate");
    const auto stats = renderSequence(dir, "late-jump.json", 14, true);
    const auto& frames = stats["frames"];
    for (int f = 0; f < 6; ++f)
        EXPECT_EQ(frames[std::size_t(f)]["accumulated"], f + 1) << "frame " << f;
    for (int f = 6; f < 14; ++f)
        EXPECT_EQ(frames[std::size_t(f)]["accumulated"], f - 5) << "frame " << f;
    // No ghost of the box where it was.
    const Image jumped = frameImage(dir, 6);
    EXPECT_EQ(redFraction(jumped, kLeftBox, kBoxRow, 4), 0.0);
    EXPECT_GT(redFraction(jumped, kRightBox, kBoxRow, 2), 0.9);
    // And it converges again: frame-to-frame differences shrink.
    const double early = meanAbsoluteDifference(frameImage(dir, 7), frameImage(dir, 8));
    const double late = meanAbsoluteDifference(frameImage(dir, 12), frameImage(dir, 13));
    std::printf("flicker after the jump: %.3g (frames 7-8), %.3g (frames 12-13)\n", early, late);
    EXPECT_LT(late, 0.5 * early);
    fs::remove_all(dir);
}

TEST(Dynamic, AStillViewFlickersLessAndLessAsFramesAccumulate) {
    const fs::path dir = scratchDir("still");
    renderSequence(dir, "", 12, true);
    const double first = meanAbsoluteDifference(frameImage(dir, 0), frameImage(dir, 1));
    const double last = meanAbsoluteDifference(frameImage(dir, 10), frameImage(dir, 11));
    std::printf("still view flicker: %.3g (frames 0-1), %.3g (frames 10-11)\n", first, last);
    EXPECT_LT(last, first / 4);
    fs::remove_all(dir);
}

TEST(Dynamic, AMovingObjectDoesNotMakeFarPixelsFlicker) {
    // Without accumulation every frame uses new random bit vectors, so a still view flickers a
    // little. The same frames with the box creeping in a corner must flicker no more far from it
    // than with the box standing still where it starts.
    const fs::path still = scratchDir("far-still"), moving = scratchDir("far-moving");
    renderSequence(still, "corner-still.json", 10, false);
    renderSequence(moving, "corner-creep.json", 10, false);
    double stillSum = 0, movingSum = 0;
    const int x0 = kSize / 2, x1 = kSize;  // the right half: far from the left corner
    for (int f = 0; f + 1 < 10; ++f) {
        stillSum += meanAbsoluteDifference(frameImage(still, f), frameImage(still, f + 1), x0, x1);
        movingSum +=
            meanAbsoluteDifference(frameImage(moving, f), frameImage(moving, f + 1), x0, x1);
    }
    std::printf("far-field flicker: still %.3g, with the moving box %.3g\n", stillSum / 9,
                movingSum / 9);
    EXPECT_LT(movingSum, 1.25 * stillSum);
    fs::remove_all(still);
    fs::remove_all(moving);
}

TEST(Dynamic, AnimationRunsAreReproducible) {
    const fs::path a = scratchDir("repro-a"), b = scratchDir("repro-b");
    renderSequence(a, "alternate.json", 6, true, 2);
    renderSequence(b, "alternate.json", 6, true, 1);
    for (int f = 0; f < 6; ++f) {
        const Image x = frameImage(a, f), y = frameImage(b, f);
        for (std::size_t i = 0; i < x.pixels.size(); ++i)
            ASSERT_EQ(x.pixels[i], y.pixels[i]) << "frame " << f << " pixel " << i;
    }
    fs::remove_all(a);
    fs::remove_all(b);
}

}  // namespace
}  // namespace igi

namespace igi {
namespace {

TEST(Dynamic, ControlCommandsMoveTheSceneWhileItRenders) {
    const fs::path dir = scratchDir("control");
    const fs::path log = dir / "master.log";
    const pid_t master = spawnProcess(
        {(binDir() / "igi-master").string(), "--scene", dynamicScene("scene.json").string(),
         "--frames", "0", "--local-clients", "1", "--listen", "127.0.0.1:0", "--control",
         "127.0.0.1:0", "--no-accumulate", "--log-level", "info"},
        log);
    ASSERT_GT(master, 0);
    const std::string controlPort = waitForControlPort(log, master);
    ASSERT_FALSE(controlPort.empty()) << readFile(log);
    auto ctl = [&](const std::vector<std::string>& args) {
        return runCtl(dir / "ctl.log", controlPort, args);
    };

    ProcessResult r = ctl({"snapshot", (dir / "before.exr").string()});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    r = ctl({"object", "box", "--translate", "0.8", "0", "0"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    r = ctl({"material", "red", "--diffuse", "0.05", "0.05", "0.8"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    r = ctl({"snapshot", (dir / "after.exr").string()});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    r = ctl({"status"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    // One epoch per frame in which commands arrived: one or two here.
    EXPECT_TRUE(r.output.find("\"epoch\":1") != std::string::npos ||
                r.output.find("\"epoch\":2") != std::string::npos)
        << r.output;
    // A bad command is refused with a reason, and the session goes on.
    r = ctl({"object", "no_such_thing", "--translate", "0", "0", "0"});
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("no_such_thing"), std::string::npos) << r.output;
    r = ctl({"stop"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    ASSERT_EQ(waitProcess(master, 60), 0) << readFile(log);

    const Image before = readFiniteImage(dir / "before.exr"),
                after = readFiniteImage(dir / "after.exr");
    EXPECT_GT(redFraction(before, kLeftBox, kBoxRow, 2), 0.9);
    EXPECT_EQ(redFraction(after, kLeftBox, kBoxRow, 4), 0.0);
    const glm::vec3 box = after.at(kRightBox, kBoxRow);
    EXPECT_GT(box.z, 3.0f * box.x) << "the box should now be blue and on the right";
    fs::remove_all(dir);
}

}  // namespace
}  // namespace igi
