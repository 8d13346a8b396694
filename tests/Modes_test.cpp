// GI modes end to end (docs/MODES.md): real master and client processes, images read back.
#include <cmath>
#include <cstdio>
#include <filesystem>

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

/// The dynamic test scene (a box moved every frame by `alternate.json`) in `mode`, `frames`
/// frames without accumulation, written to `dir`/frame_NN.exr.
void renderAnimation(const fs::path& dir, const std::string& mode, int clients, int frames) {
    const ProcessResult r = runProcess(
        masterCommand({"--scene", dynamicData("scene.json").string(), "--animation",
                       dynamicData("alternate.json").string(), "--gi", mode, "--frames",
                       std::to_string(frames), "--local-clients", std::to_string(clients),
                       "--no-accumulate", "--output-sequence", (dir / "frame_%02d.exr").string()}),
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

// Every client keeps the same pool of photons whatever tiles it renders: each epoch's batch is
// a function of the seed, the epoch and that epoch's scene only.
TEST(Modes, StreamAnimationIsTheSameWithOneAndThreeClients) {
    const fs::path one = scratchDir("stream-one"), three = scratchDir("stream-three");
    renderAnimation(one, "stream", 1, 6);
    renderAnimation(three, "stream", 3, 6);
    for (int f = 0; f < 6; ++f) expectSameImage(frameFile(one, f), frameFile(three, f));
    fs::remove_all(one);
    fs::remove_all(three);
}

// The mode is what lights the frames after a change: not IGI's image, but the same light
// within what clustering photons onto surface lights costs.
TEST(Modes, StreamFirstFramesAreItsOwnAndAsBrightAsIgis) {
    const fs::path igi = scratchDir("first-igi"), stream = scratchDir("first-stream");
    renderAnimation(igi, "igi", 1, 4);
    renderAnimation(stream, "stream", 1, 4);
    for (int f = 0; f < 4; ++f) {
        const Image a = readFiniteImage(frameFile(igi, f)),
                    b = readFiniteImage(frameFile(stream, f));
        ASSERT_EQ(a.pixels.size(), b.pixels.size());
        EXPECT_TRUE(a.pixels != b.pixels) << "frame " << f << ": --gi stream rendered IGI's image";
        const double ma = meanLuminance(a), mb = meanLuminance(b);
        EXPECT_NEAR(mb / ma, 1.0, 0.05) << "frame " << f;
    }
    fs::remove_all(igi);
    fs::remove_all(stream);
}

// A still view converges in every mode to the rendering equation's answer: the accumulated
// frames are the converging estimator, the stream's first frame weighs 1 / frames.
TEST(Modes, StreamStillSceneConvergesToThePathTracersMean) {
    const fs::path dir = scratchDir("stream-still");
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
    const Image stream = render({"--gi", "stream", "--frames", "128"}, "stream.exr");
    EXPECT_NEAR(meanLuminance(stream) / meanLuminance(reference), 1.0, 0.02);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace igi
