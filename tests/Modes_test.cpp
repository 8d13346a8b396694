// GI modes end to end (docs/MODES.md): real master and client processes, images read back.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>

#include <gtest/gtest.h>

#include "Session.h"
#include "image/ImageIO.h"
#include "math/Color.h"

namespace igi {
namespace {

using namespace igi::testing;
namespace fs = std::filesystem;

fs::path dynamicData(const std::string& file) {
    return sourceDir() / "tests/data/dynamic" / file;
}

/// The dynamic test scene (a box moved every frame by `alternate.json`, or by `animation`) in
/// `mode`, `frames` frames without accumulation, written to `dir`/frame_NN.exr.
void renderAnimation(const fs::path& dir, const std::string& mode, int clients, int frames,
                     const std::string& animation = "alternate.json") {
    const ProcessResult r = runProcess(
        masterCommand({"--scene", dynamicData("scene.json").string(), "--animation",
                       dynamicData(animation).string(), "--gi", mode, "--frames",
                       std::to_string(frames), "--local-clients", std::to_string(clients),
                       "--no-accumulate", "--output-sequence", (dir / "frame_%02d.exr").string()}),
        dir / "master.log");
    ASSERT_EQ(r.exitCode, 0) << r.output;
}

/// The example animation (scenes/cornell/example.anim.json: objects, the light and the camera
/// moving, 48 frames) at 80 x 60 in `mode`, without accumulation, written to `dir`/frame_NN.exr.
void renderExample(const fs::path& dir, const std::string& mode, int clients) {
    const fs::path cornell = sourceDir() / "scenes/cornell";
    const ProcessResult r =
        runProcess(masterCommand({"--scene", (cornell / "cornell.json").string(), "--animation",
                                  (cornell / "example.anim.json").string(), "--gi", mode,
                                  "--frames", "48", "--width", "80", "--height", "60",
                                  "--local-clients", std::to_string(clients), "--no-accumulate",
                                  "--output-sequence", (dir / "frame_%02d.exr").string()}),
                   dir / "master.log");
    ASSERT_EQ(r.exitCode, 0) << r.output;
}

fs::path frameFile(const fs::path& dir, int frame) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%02d.exr", frame);
    return dir / name;
}

double meanLuminance(const Image& image) {
    double sum = 0;
    for (const glm::vec3& p : image.pixels) sum += luminance(p);
    return sum / double(image.pixels.size());
}

// Every client keeps the same lighting whatever tiles it renders: photon streaming's batch of
// each epoch is a function of the seed, the epoch and that epoch's scene only; selective photon
// tracing's pool of each frame a function of the scene of every frame before.
void expectSameAnimationWithOneAndThreeClients(const std::string& mode,
                                               const std::string& animation = "alternate.json",
                                               int frames = 6) {
    const fs::path one = scratchDir(mode + "-one"), three = scratchDir(mode + "-three");
    renderAnimation(one, mode, 1, frames, animation);
    renderAnimation(three, mode, 3, frames, animation);
    for (int f = 0; f < frames; ++f) expectSameImage(frameFile(one, f), frameFile(three, f));
    fs::remove_all(one);
    fs::remove_all(three);
}

void expectSameExampleWithOneAndThreeClients(const std::string& mode) {
    const fs::path one = scratchDir(mode + "-example-one"),
                   three = scratchDir(mode + "-example-three");
    renderExample(one, mode, 1);
    renderExample(three, mode, 3);
    for (int f = 0; f < 48; ++f) expectSameImage(frameFile(one, f), frameFile(three, f));
    fs::remove_all(one);
    fs::remove_all(three);
}

TEST(Modes, StreamAnimationIsTheSameWithOneAndThreeClients) {
    expectSameAnimationWithOneAndThreeClients("stream");
    expectSameExampleWithOneAndThreeClients("stream");
}

TEST(Modes, SptAnimationIsTheSameWithOneAndThreeClients) {
    expectSameAnimationWithOneAndThreeClients("spt");
    // A jump, then a still scene whose frames go on tracing the touched groups (within one
    // epoch, counted from its first frame).
    expectSameAnimationWithOneAndThreeClients("spt", "jump.json", 8);
    expectSameExampleWithOneAndThreeClients("spt");
}

// Instant caching's records are a function of the scene state only: a client that computed a
// record anew and one that brought it up to date after a move hold the same bits.
TEST(Modes, CacheAnimationIsTheSameWithOneAndThreeClients) {
    expectSameAnimationWithOneAndThreeClients("cache");
    expectSameAnimationWithOneAndThreeClients("cache", "jump.json", 8);
    expectSameExampleWithOneAndThreeClients("cache");
}

// Simulated photon mapping's emission of a frame is a function of the scene of every frame
// before (the round robin goes on while the scene holds still), its reconstruction a function
// of the emission; the screen-space caustics are the frame's photons, whichever tile asks.
TEST(Modes, PhotonmapAnimationIsTheSameWithOneAndThreeClients) {
    expectSameAnimationWithOneAndThreeClients("photonmap");
    expectSameAnimationWithOneAndThreeClients("photonmap", "jump.json", 8);
    expectSameExampleWithOneAndThreeClients("photonmap");
}

// A client that joins mid-animation replays the epochs the master sends with its scene
// (SceneData's history) and holds the lighting the first client holds: the session's frames
// are bit for bit those of a session with that one client alone.
void expectAJoinerHoldsTheSameLighting(const std::string& mode) {
    const fs::path dir = scratchDir(mode + "-join");
    const fs::path secret = dir / "secret", slide = dir / "slide.json";
    std::ofstream(secret) << "the render cluster's shared secret\n";
    // The box slides a little every frame: every frame is a new epoch.
    std::ofstream(slide) << R"({"objects": {"mirror_box": [)"
                         << R"({"frame": 0, "translate": [-0.38, 0, -0.3]},)"
                         << R"({"frame": 5000, "translate": [0.3, 0, -0.3]}]}})";
    const std::vector<std::string> mine = {"--animation",     slide.string(),    "--gi", mode,
                                           "--no-accumulate", "--local-clients", "1"};
    std::vector<std::string> extra = mine;
    extra.insert(extra.end(), {"--secret-file", secret.string(), "--output-sequence",
                               (dir / "join_%04d.exr").string()});
    OpenSession session(dir, extra);
    ASSERT_TRUE(session.started()) << readFile(session.log);
    ASSERT_TRUE(session.waitFrames(3)) << readFile(session.log);
    // Frames finished before the joiner exists cannot hold its tiles; the frame in flight may,
    // however far ahead the master assigns tiles.
    const int finishedBeforeJoin = session.lastFrame();
    const pid_t joiner = session.join(secret, 2);
    ASSERT_GT(joiner, 0) << readFile(session.log) << readFile(dir / "joiner.log");
    ASSERT_TRUE(session.waitFrames(10)) << readFile(session.log);
    const int frames = session.stop();
    ASSERT_GT(frames, 0) << readFile(session.log);
    EXPECT_EQ(waitProcess(joiner, 30), 0) << readFile(dir / "joiner.log");
    std::ifstream statsFile(dir / "stats.json");
    const auto stats = nlohmann::json::parse(statsFile);
    ASSERT_EQ(stats["clients"].size(), 2u);
    ASSERT_GT(stats["clients"][1]["tiles"].get<int>(), 0) << "the joiner never got a tile";
    EXPECT_GT(stats["clients"][1]["first_frame"].get<std::int64_t>(), finishedBeforeJoin)
        << "it joined after frame " << finishedBeforeJoin;

    auto args = sceneArgs(frames);
    args.insert(args.end(), mine.begin(), mine.end());
    args.insert(args.end(), {"--output-sequence", (dir / "alone_%04d.exr").string()});
    const ProcessResult alone = runProcess(masterCommand(args), dir / "alone.log");
    ASSERT_EQ(alone.exitCode, 0) << alone.output;
    for (int f = 0; f < frames; ++f) {
        char a[32], b[32];
        std::snprintf(a, sizeof a, "join_%04d.exr", f);
        std::snprintf(b, sizeof b, "alone_%04d.exr", f);
        expectSameImage(dir / a, dir / b);
    }
    fs::remove_all(dir);
}

TEST(Modes, AStreamJoinerHoldsThePoolTheOthersHold) {
    expectAJoinerHoldsTheSameLighting("stream");
}

TEST(Modes, AnSptJoinerHoldsThePoolTheOthersHold) {
    expectAJoinerHoldsTheSameLighting("spt");
}

TEST(Modes, CacheAndPhotonmapJoinersHoldTheLightTheOthersHold) {
    expectAJoinerHoldsTheSameLighting("cache");      // no history: its records, computed anew
    expectAJoinerHoldsTheSameLighting("photonmap");  // the emission replayed from the history
}

// The mode is what lights the frames after a change: not IGI's image, but the same light
// within what the mode's approximation costs (clustering photons onto surface lights, or light
// kept from before the change).
void expectOwnFirstFramesAsBrightAsIgis(const std::string& mode) {
    const fs::path igi = scratchDir(mode + "-first-igi"), own = scratchDir("first-" + mode);
    renderAnimation(igi, "igi", 1, 4);
    renderAnimation(own, mode, 1, 4);
    for (int f = 0; f < 4; ++f) {
        const Image a = readFiniteImage(frameFile(igi, f)), b = readFiniteImage(frameFile(own, f));
        ASSERT_EQ(a.pixels.size(), b.pixels.size());
        EXPECT_TRUE(a.pixels != b.pixels)
            << "frame " << f << ": --gi " << mode << " rendered IGI's image";
        const double ma = meanLuminance(a), mb = meanLuminance(b);
        EXPECT_NEAR(mb / ma, 1.0, 0.05) << "frame " << f;
    }
    fs::remove_all(igi);
    fs::remove_all(own);
}

TEST(Modes, StreamFirstFramesAreItsOwnAndAsBrightAsIgis) {
    expectOwnFirstFramesAsBrightAsIgis("stream");
}

TEST(Modes, SptFirstFramesAreItsOwnAndAsBrightAsIgis) {
    expectOwnFirstFramesAsBrightAsIgis("spt");
}

TEST(Modes, CacheAndPhotonmapFirstFramesAreTheirOwnAndAsBrightAsIgis) {
    expectOwnFirstFramesAsBrightAsIgis("cache");
    expectOwnFirstFramesAsBrightAsIgis("photonmap");
}

// A still view converges in every mode to the rendering equation's answer: the accumulated
// frames are the converging estimator, the mode's first frame weighs 1 / frames.
TEST(Modes, StillSceneConvergesToThePathTracersMeanInEveryMode) {
    const fs::path dir = scratchDir("modes-still");
    const std::vector<std::string> scene = {
        "--scene",         (sourceDir() / "scenes/cornell/cornell.json").string(),
        "--width",         "64",
        "--height",        "48",
        "--local-clients", "1"};
    auto render = [&](std::vector<std::string> extra, const std::string& out) {
        std::vector<std::string> args = scene;
        args.insert(args.end(), extra.begin(), extra.end());
        args.insert(args.end(), {"--output", (dir / out).string()});
        const ProcessResult r = runProcess(masterCommand(args), dir / (out + ".log"));
        EXPECT_EQ(r.exitCode, 0) << r.output;
        return readFiniteImage(dir / out);
    };
    const Image reference =
        render({"--integrator", "path", "--spp", "64", "--frames", "8"}, "path.exr");
    for (const std::string mode : {"igi", "spt", "stream", "cache", "photonmap"}) {
        const Image image = render({"--gi", mode, "--frames", "128"}, mode + ".exr");
        EXPECT_NEAR(meanLuminance(image) / meanLuminance(reference), 1.0, 0.02) << mode;
    }
    fs::remove_all(dir);
}

}  // namespace
}  // namespace igi
