// The environment changed while a session renders, with real processes: by a control command
// (the image brightens by the factor) and by an animation (3 clients give the bits of 1).
#include <filesystem>
#include <regex>

#include <gtest/gtest.h>

#include "Session.h"
#include "image/ImageIO.h"
#include "math/Color.h"

namespace igi {
namespace {

using namespace igi::testing;
namespace fs = std::filesystem;

// tests/data/dynamic/sky.json: a floor and a box under a constant sky of radiance 0.5, seen
// from above; nothing else lights it, so its image is linear in the sky's radiance.
fs::path skyScene() {
    return sourceDir() / "tests/data/dynamic/sky.json";
}

double meanLuminance(const Image& image) {
    double sum = 0;
    for (const glm::vec3& p : image.pixels) sum += luminance(p);
    return sum / double(image.pixels.size());
}

TEST(LiveEnvironment, AControlCommandScalesTheSkyAndTheImageBrightensByTheFactor) {
    const fs::path dir = scratchDir("live-sky");
    const fs::path log = dir / "master.log";
    const pid_t master =
        spawnProcess({(binDir() / "igi-master").string(), "--scene", skyScene().string(),
                      "--frames", "0", "--local-clients", "2", "--listen", "127.0.0.1:0",
                      "--control", "127.0.0.1:0", "--log-level", "info"},
                     log);
    ASSERT_GT(master, 0);
    const std::string controlPort = waitForControlPort(log, master);
    ASSERT_FALSE(controlPort.empty()) << readFile(log);
    auto ctl = [&](const std::vector<std::string>& args) {
        return runCtl(dir / "ctl.log", controlPort, args);
    };

    // Snapshots of the accumulated image: several frames each, so that their noise is small
    // beside the factor.
    ProcessResult r = ctl({"snapshot", (dir / "before.exr").string()});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    r = ctl({"snapshot", (dir / "before.exr").string()});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    r = ctl({"environment", "--scale", "4"});  // radiance 0.5 -> 4
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("\"changes\":1"), std::string::npos) << r.output;
    for (int i = 0; i < 3; ++i) {
        r = ctl({"snapshot", (dir / "after.exr").string()});
        ASSERT_EQ(r.exitCode, 0) << r.output;
    }
    // A bad value is refused with its key, and the session goes on.
    r = ctl({"environment", "--scale", "-1"});
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("/scale"), std::string::npos) << r.output;
    r = ctl({"stop"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    ASSERT_EQ(waitProcess(master, 60), 0) << readFile(log);

    const double before = meanLuminance(readFiniteImage(dir / "before.exr")),
                 after = meanLuminance(readFiniteImage(dir / "after.exr"));
    std::printf("mean luminance under the sky: %.5f, after scaling it by 8: %.5f (x %.4f)\n",
                before, after, after / before);
    EXPECT_GT(before, 0.05);
    EXPECT_NEAR(after / before, 8.0, 0.1 * 8.0);  // different frames: noise of a few %
    fs::remove_all(dir);
}

// The sky brightens, turns colour and rotates frame by frame; three clients render every frame
// with the bits one client gives (each applies the same changes to the same state).
TEST(LiveEnvironment, ThreeClientsRenderAnAnimatedSkyExactlyAsOneDoes) {
    const fs::path dir = scratchDir("sky-pulse");
    auto render = [&](int clients) {
        const fs::path out = dir / std::to_string(clients);
        fs::create_directories(out);
        const ProcessResult r =
            runProcess({(binDir() / "igi-master").string(), "--scene", skyScene().string(),
                        "--animation", (sourceDir() / "tests/data/dynamic/sky-pulse.json").string(),
                        "--frames", "4", "--local-clients", std::to_string(clients), "--listen",
                        "127.0.0.1:0", "--output-sequence", (out / "frame_%02d.exr").string()},
                       out / "master.log");
        EXPECT_EQ(r.exitCode, 0) << r.output;
        return out;
    };
    const fs::path three = render(3), one = render(1);
    for (int f = 0; f < 4; ++f) {
        char name[32];
        std::snprintf(name, sizeof name, "frame_%02d.exr", f);
        expectSameImage(three / name, one / name);
    }
    // The sky of frame 3 is 2, 1.5, 1 times 1 against 0.5 grey at frame 0: red rises most.
    const Image first = readFiniteImage(three / "frame_00.exr"),
                last = readFiniteImage(three / "frame_03.exr");
    double red0 = 0, red3 = 0, blue0 = 0, blue3 = 0;
    for (std::size_t i = 0; i < first.pixels.size(); ++i) {
        red0 += first.pixels[i].x, red3 += last.pixels[i].x;
        blue0 += first.pixels[i].z, blue3 += last.pixels[i].z;
    }
    EXPECT_NEAR(red3 / red0, 4.0, 0.4);
    EXPECT_NEAR(blue3 / blue0, 2.0, 0.2);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace igi
