// Render settings changed while a session runs (`igi-ctl settings`), with real processes: from
// the frame of the change on, the images are those of a session started with the new settings
// at that frame (igi-master --first-frame), in igi and in a mode that keeps lighting across
// epochs; a value out of range is refused, naming the key and its range, and the session goes
// on as it was.
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "Session.h"

namespace igi {
namespace {

using namespace igi::testing;
namespace fs = std::filesystem;

// Frames compared after the change: the first (where a stateful mode's lighting starts anew)
// and some accumulated ones.
constexpr int kFramesAfter = 3;

fs::path sequenceFrame(const fs::path& dir, const std::string& prefix, int frame) {
    char name[64];
    std::snprintf(name, sizeof name, "%s_%04d.exr", prefix.c_str(), frame);
    return dir / name;
}

// The reply of an igi-ctl command, as JSON (null when it is not JSON).
nlohmann::json replyOf(const ProcessResult& r) {
    const std::string line = r.output.substr(0, r.output.find('\n'));
    return nlohmann::json::parse(line, nullptr, false);
}

/// What a test changes: the options of both sessions (`common`), the live one's settings before
/// the change (`before`), the igi-ctl settings command's pairs (`command`) and the fresh
/// session's options for the settings after it (`after`); and whether a client joins after the
/// change (it must render with the settings in force).
struct Change {
    std::vector<std::string> common, before, command, after;
    bool joiner = false;
};

/// Starts a client that joins `live` (started with --secret-file `secret`) and waits until it
/// is ready; returns the last frame to compare: a few frames past the last one finished
/// before it was ready, so that frames it renders tiles of are among them.
int joinAfterTheChange(OpenSession& live, const fs::path& secret, pid_t& joiner) {
    joiner =
        spawnProcess({(binDir() / "igi-client").string(), "--connect", "127.0.0.1:" + live.port,
                      "--threads", "1", "--secret-file", secret.string()},
                     live.dir / "joiner.log");
    if (waitForLine(live.log, std::regex(R"(client 3 \(.*\) is ready)"), live.master).empty())
        return -1;
    // The last frame finished before it was ready (frames open then may still go to the others).
    const std::string text = readFile(live.log);
    const std::string before = text.substr(0, text.find("client 3 ("));
    const std::regex frameLine(R"(frame +(\d+):)");
    int last = 0;
    for (std::sregex_iterator it(before.begin(), before.end(), frameLine), end; it != end; ++it)
        last = std::stoi((*it)[1].str());
    return last + 6;
}

/// A live session changes its settings by `igi-ctl settings` after a few frames; a second
/// session, started with the settings after the change at the frame the first one's reply
/// names (--first-frame), renders the same images from there on, bit for bit.
void expectChangeEqualsFreshSession(const std::string& name, const Change& c) {
    const fs::path dir = scratchDir(name);
    const fs::path secret = dir / "secret";
    std::ofstream(secret) << "the render cluster's shared secret\n";
    int changedAt = -1, lastCompared = -1;
    nlohmann::json settingsInForce;
    pid_t joiner = -1;
    {
        std::vector<std::string> extra = {"--local-clients", "2", "--output-sequence",
                                          (dir / "live_%04d.exr").string()};
        if (c.joiner) extra.insert(extra.end(), {"--secret-file", secret.string()});
        extra.insert(extra.end(), c.common.begin(), c.common.end());
        extra.insert(extra.end(), c.before.begin(), c.before.end());
        OpenSession live(dir, extra);
        ASSERT_TRUE(live.started()) << readFile(live.log);
        // Past frame 3: after an animation's change at frame 2 (spt below).
        ASSERT_FALSE(waitForLine(live.log, std::regex("frame +3:"), live.master, 300).empty())
            << readFile(live.log);
        std::vector<std::string> args = {"settings"};
        args.insert(args.end(), c.command.begin(), c.command.end());
        const ProcessResult r = runCtl(dir / "ctl.log", live.controlPort, args);
        ASSERT_EQ(r.exitCode, 0) << r.output;
        const nlohmann::json reply = replyOf(r);
        ASSERT_TRUE(reply.is_object() && reply.value("ok", false)) << r.output;
        changedAt = reply.at("from_frame").get<int>();
        ASSERT_TRUE(reply.contains("settings")) << r.output;
        settingsInForce = reply["settings"];
        lastCompared = changedAt + kFramesAfter - 1;
        if (c.joiner) {
            lastCompared = joinAfterTheChange(live, secret, joiner);
            ASSERT_GT(lastCompared, changedAt)
                << "the joiner was never ready:\n"
                << readFile(live.log) << readFile(dir / "joiner.log");
        }
        ASSERT_FALSE(waitForLine(live.log,
                                 std::regex("frame +" + std::to_string(lastCompared) + ":"),
                                 live.master, 300)
                         .empty())
            << readFile(live.log);
        ASSERT_GE(live.stop(), lastCompared + 1) << readFile(live.log);
    }
    // The statistics name the frame from which the new settings are in force, and only it.
    std::ifstream statsFile(dir / "stats.json");
    const auto stats = nlohmann::json::parse(statsFile);
    int framesWithSettings = 0;
    for (const auto& frame : stats.at("frames")) {
        if (!frame.contains("settings")) continue;
        ++framesWithSettings;
        EXPECT_EQ(frame.at("index").get<int>(), changedAt);
        EXPECT_EQ(frame.at("settings"), settingsInForce);
    }
    EXPECT_EQ(framesWithSettings, 1);
    if (c.joiner) {
        EXPECT_EQ(waitProcess(joiner, 30), 0) << readFile(dir / "joiner.log");
        ASSERT_EQ(stats["clients"].size(), 3u);
        EXPECT_GT(stats["clients"][2]["tiles"].get<int>(), 0) << "the joiner never got a tile";
    }
    // The log says where the settings changed, and the clients did not load the scene again.
    const std::string liveLog = readFile(dir / "master.log");
    EXPECT_NE(liveLog.find("igi-ctl command at frame " + std::to_string(changedAt)),
              std::string::npos)
        << liveLog;
    const std::regex ready(R"(client \d+ \(.*\) is ready)");
    EXPECT_EQ(std::distance(std::sregex_iterator(liveLog.begin(), liveLog.end(), ready),
                            std::sregex_iterator()),
              c.joiner ? 3 : 2)
        << "each client loads the scene once\n"
        << liveLog;

    std::vector<std::string> args = sceneArgs(lastCompared - changedAt + 1);
    args.insert(args.end(), {"--local-clients", "1", "--first-frame", std::to_string(changedAt),
                             "--output-sequence", (dir / "fresh_%04d.exr").string()});
    args.insert(args.end(), c.common.begin(), c.common.end());
    args.insert(args.end(), c.after.begin(), c.after.end());
    const ProcessResult fresh = runProcess(masterCommand(args), dir / "fresh.log");
    ASSERT_EQ(fresh.exitCode, 0) << fresh.output;
    for (int f = changedAt; f <= lastCompared; ++f) {
        SCOPED_TRACE("frame " + std::to_string(f));
        expectSameImage(sequenceFrame(dir, "live", f), sequenceFrame(dir, "fresh", f));
    }
    // The frame before the change was rendered with the old settings: not the fresh session's.
    EXPECT_FALSE(fs::exists(sequenceFrame(dir, "fresh", changedAt - 1)));
    // And the change changed something: a session that kept the old settings there does not
    // render the same frames (so the equality above is not that of two unchanged sessions).
    // The last of them is compared: a change of the accumulation shows from the second frame.
    const int last = changedAt + kFramesAfter - 1;
    args = sceneArgs(kFramesAfter);
    args.insert(args.end(), {"--local-clients", "1", "--first-frame", std::to_string(changedAt),
                             "--output-sequence", (dir / "unchanged_%04d.exr").string()});
    args.insert(args.end(), c.common.begin(), c.common.end());
    args.insert(args.end(), c.before.begin(), c.before.end());
    const ProcessResult unchanged = runProcess(masterCommand(args), dir / "unchanged.log");
    ASSERT_EQ(unchanged.exitCode, 0) << unchanged.output;
    const Image a = readFiniteImage(sequenceFrame(dir, "live", last)),
                b = readFiniteImage(sequenceFrame(dir, "unchanged", last));
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) differing += a.pixels[i] != b.pixels[i];
    EXPECT_GT(differing, a.pixels.size() / 10) << "pixels the new settings changed";
    fs::remove_all(dir);
}

TEST(Settings, AChangeInIgiEqualsASessionStartedWithTheNewSettingsAtThatFrame) {
    expectChangeEqualsFreshSession(
        "settings-igi",
        {.common = {},
         .before = {},
         .command = {"indirect_vpls", "40", "direct_samples", "2", "light_sampling", "power"},
         .after = {"--indirect-vpls", "40", "--direct-samples", "2", "--light-sampling", "power"}});
}

// An animation (in a scratch folder named `name`) in which the glass ball jumps at frame 2: a
// new epoch, whose lighting a stateful mode carries on, before the settings change.
fs::path ballJumpingAtFrame2(const std::string& name) {
    const fs::path animation = scratchDir(name) / "jump.json";
    std::ofstream(animation) << R"({"objects": {"glass_ball": [
        {"frame": 0, "translate": [0.42, 0.36, 0.3]},
        {"frame": 1, "translate": [0.42, 0.36, 0.3]},
        {"frame": 2, "translate": [-0.3, 0.36, 0.45]}]}})";
    return animation;
}

// Selective photon tracing keeps its photon groups across epochs: at new settings every client
// starts them anew, as a session started there does. The glass ball jumps at frame 2, and with
// one group traced again per frame most groups still hold the light of before when the
// settings change: a client that kept them would light the frame differently.
TEST(Settings, AChangeInSelectivePhotonTracingEqualsASessionStartedWithItAtThatFrame) {
    const fs::path animation = ballJumpingAtFrame2("settings-spt-animation");
    expectChangeEqualsFreshSession("settings-spt",
                                   {.common = {"--gi", "spt", "--animation", animation.string()},
                                    .before = {"--spt-budget", "1"},
                                    .command = {"spt_budget", "12", "direct_samples", "2"},
                                    .after = {"--spt-budget", "12", "--direct-samples", "2"}});
    fs::remove_all(animation.parent_path());
}

// Photon streaming fills its pool afresh at new settings; its batches are keyed by the frame
// their epoch begins at, so the pool is a fresh session's there. The glass ball moves at frame 2
// (a new epoch and batch before the change).
TEST(Settings, AChangeInPhotonStreamingEqualsASessionStartedWithItAtThatFrame) {
    const fs::path animation = ballJumpingAtFrame2("settings-stream-animation");
    expectChangeEqualsFreshSession("settings-stream",
                                   {.common = {"--gi", "stream", "--animation", animation.string()},
                                    .before = {"--stream-window", "4"},
                                    .command = {"stream_window", "6", "direct_samples", "2"},
                                    .after = {"--stream-window", "6", "--direct-samples", "2"}});
    fs::remove_all(animation.parent_path());
}

// Another GI mode: the clients switch methods at the same frame, without loading the scene
// again, and light as a session started in that mode there would.
TEST(Settings, SwitchingFromIgiToPhotonMappingEqualsASessionStartedInItAtThatFrame) {
    expectChangeEqualsFreshSession("settings-gi", {.common = {},
                                                   .before = {},
                                                   .command = {"gi", "photonmap"},
                                                   .after = {"--gi", "photonmap"}});
}

// The settings the master makes its frames with (the tile layout, the discontinuity buffer, the
// accumulation) change too: the frames in flight finish the old way, and from the change on
// the images are a session's started with the new ones.
TEST(Settings, AChangeOfInterleavingAndFilterEqualsASessionStartedWithThemAtThatFrame) {
    expectChangeEqualsFreshSession(
        "settings-interleave",
        {.common = {},
         .before = {},
         .command = {"interleave", "[2,2]", "filter", "[4,4]", "filter_depth_threshold", "0.2"},
         .after = {"--interleave", "2x2", "--filter", "4x4", "--filter-depth-threshold", "0.2"}});
}

TEST(Settings, TurningAccumulationOffAndTheProgressiveFilterOffEqualsAFreshSession) {
    expectChangeEqualsFreshSession("settings-accumulate",
                                   {.common = {},
                                    .before = {},
                                    .command = {"accumulate", "false", "converge", "false"},
                                    .after = {"--no-accumulate", "--converge", "off"}});
}

// A client that joins after the change renders with the settings in force: every frame from the
// change on, those it has tiles of among them, is still the fresh session's.
TEST(Settings, AClientJoiningAfterAChangeRendersWithTheSettingsInForce) {
    expectChangeEqualsFreshSession("settings-join",
                                   {.common = {},
                                    .before = {},
                                    .command = {"indirect_vpls", "40", "caustic_photons", "100"},
                                    .after = {"--indirect-vpls", "40", "--caustic-photons", "100"},
                                    .joiner = true});
}

// The target error changes too (it is the master's: no new epoch). A live session idle at its
// target renders again when the target is lowered, or when the settings change; then, at the
// target again, it idles again.
TEST(Settings, ALowerTargetOrNewSettingsResumeASessionIdleAtItsTarget) {
    const fs::path dir = scratchDir("settings-target");
    // A target the second frame meets.
    OpenSession live(dir, {"--local-clients", "1", "--target-error", "1"});
    ASSERT_TRUE(live.started()) << readFile(live.log);
    const std::regex idle(R"(rendering ends; the session stays live, idle)");
    ASSERT_FALSE(waitForLine(live.log, idle, live.master).empty()) << readFile(live.log);
    auto ctl = [&](const std::vector<std::string>& args) {
        return replyOf(runCtl(dir / "ctl.log", live.controlPort, args));
    };
    auto count = [&](const std::regex& line) {
        const std::string text = readFile(live.log);
        return std::distance(std::sregex_iterator(text.begin(), text.end(), line),
                             std::sregex_iterator());
    };
    EXPECT_EQ(ctl({"status"}).value("rendering", ""), "idle");

    // Lowered: rendering resumes, with the same scene (no new epoch).
    const int epoch = ctl({"status"}).value("epoch", -1);
    nlohmann::json reply = ctl({"settings", "target_error", "0.000001"});
    ASSERT_TRUE(reply.value("ok", false)) << reply.dump();
    EXPECT_EQ(reply.value("target_error", 0.0), 0.000001);
    EXPECT_EQ(reply.value("changes", -1), 0) << reply.dump();
    const std::regex resumes(R"(rendering resumes at frame)");
    ASSERT_FALSE(waitForLine(live.log, resumes, live.master).empty()) << readFile(live.log);
    ASSERT_TRUE(live.waitFrames(2)) << readFile(live.log);
    nlohmann::json status = ctl({"status"});
    EXPECT_EQ(status.value("rendering", ""), "running") << status.dump();
    EXPECT_EQ(status.value("target_error", 0.0), 0.000001);
    EXPECT_EQ(status.value("epoch", -2), epoch) << status.dump();

    // Raised to what the image meets: idle again.
    ASSERT_TRUE(ctl({"settings", "target_error", "1"}).value("ok", false));
    for (int i = 0; i < 600 && count(idle) < 2; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    ASSERT_EQ(count(idle), 2) << readFile(live.log);

    // New settings while idle: a new epoch, rendered, until the target is met again.
    reply = ctl({"settings", "indirect_vpls", "40"});
    ASSERT_TRUE(reply.value("ok", false)) << reply.dump();
    for (int i = 0; i < 600 && count(idle) < 3; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    ASSERT_EQ(count(idle), 3) << readFile(live.log);
    EXPECT_EQ(count(resumes), 2) << readFile(live.log);
    status = ctl({"status"});
    EXPECT_EQ(status.value("epoch", -2), epoch + 1) << status.dump();
    EXPECT_EQ(status["settings"].value("indirect_vpls", 0), 40) << status.dump();

    // Out of range: refused with the key and its range.
    reply = ctl({"settings", "target_error", "-1"});
    EXPECT_FALSE(reply.value("ok", true));
    EXPECT_NE(reply.value("error", "").find("/target_error: must be in [0, 100], got -1"),
              std::string::npos)
        << reply.dump();
    EXPECT_GT(live.stop(), 0);
    fs::remove_all(dir);
}

// Out of range, unknown, or fixed for the session: refused with the key (and its range), and the
// session renders on with the settings it had.
TEST(Settings, ABadValueIsRefusedNamingTheKeyAndItsRangeAndChangesNothing) {
    const fs::path dir = scratchDir("settings-bad");
    OpenSession live(dir, {"--local-clients", "1"});
    ASSERT_TRUE(live.started()) << readFile(live.log);
    ASSERT_TRUE(live.waitFrames(1)) << readFile(live.log);
    auto status = [&] { return replyOf(runCtl(dir / "ctl.log", live.controlPort, {"status"})); };
    const nlohmann::json before = status();
    ASSERT_TRUE(before.is_object()) << readFile(dir / "ctl.log");

    struct Case {
        std::vector<std::string> args;
        std::string expected;
    };
    const Case cases[] = {
        {{"settings", "indirect_vpls", "200000"},
         "control command: /indirect_vpls: must be in [0, 100000], got 200000"},
        {{"settings", "clamp_distance", "1.5"}, "/clamp_distance: must be in [0, 1)"},
        {{"settings", "light_sampling", "best"},
         "/light_sampling: unknown value 'best' (expected one of: auto, power, tree)"},
        {{"settings", "indirect_vpl", "8"}, "/indirect_vpl: unknown key"},
        {{"settings", "tile_size", "16"}, "/tile_size: 'tile_size' is fixed"},
        // One bad key refuses the whole command: the good one does not change either.
        {{"settings", "direct_samples", "2", "caustic_photons", "-1"},
         "/caustic_photons: must be in [0, 10000000], got -1"},
    };
    for (const Case& c : cases) {
        const ProcessResult r = runCtl(dir / "ctl.log", live.controlPort, c.args);
        EXPECT_EQ(r.exitCode, 1) << r.output;
        const nlohmann::json reply = replyOf(r);
        ASSERT_TRUE(reply.is_object()) << r.output;
        EXPECT_FALSE(reply.value("ok", true)) << r.output;
        EXPECT_NE(reply.value("error", "").find(c.expected), std::string::npos) << r.output;
    }
    // Nothing changed: the same settings, the same epoch, and frames go on.
    ASSERT_TRUE(live.waitFrames(2)) << readFile(live.log);
    const nlohmann::json after = status();
    EXPECT_EQ(after.at("settings"), before.at("settings"));
    EXPECT_EQ(after.at("epoch"), before.at("epoch"));
    EXPECT_GT(after.at("frames_done").get<int>(), before.at("frames_done").get<int>());
    EXPECT_GT(live.stop(), 0);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace igi
