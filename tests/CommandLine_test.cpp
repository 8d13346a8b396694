// Issue 40, "the first afternoon": what a newcomer trips over on igi-master's and igi-ctl's
// command lines and in their logs, each with the real processes.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "BuildId.h"
#include "Session.h"

namespace igi {
namespace {

using namespace igi::testing;
namespace fs = std::filesystem;

nlohmann::json replyOf(const ProcessResult& r) {
    return nlohmann::json::parse(r.output, nullptr, false);
}

double meanLuminance(const Image& image) {
    double sum = 0;
    for (const auto& p : image.pixels) sum += luminance(p);
    return sum / double(std::max<std::size_t>(1, image.pixels.size()));
}

// Item 2: outputs are checked before the first frame, and one that cannot be written at the
// end does not cost the others theirs.
TEST(CommandLine, OutputsAreCheckedBeforeTheFirstFrameAndOneFailingSparesTheOthers) {
    const fs::path dir = scratchDir("outputs");
    const ProcessResult jpg = runMaster(
        dir / "jpg.log", 30,
        {"--output", (dir / "out.jpg").string(), "--output", (dir / "good.png").string()});
    EXPECT_EQ(jpg.exitCode, 2) << jpg.output;
    EXPECT_TRUE(contains(
        jpg.output, "--output " + (dir / "out.jpg").string() + ": unsupported image type '.jpg'"))
        << jpg.output;
    EXPECT_FALSE(contains(jpg.output, "clients ready")) << "refused only after rendering";
    const ProcessResult proc = runMaster(dir / "proc.log", 30, {"--output", "/proc/x.png"});
    EXPECT_EQ(proc.exitCode, 2) << proc.output;
    EXPECT_TRUE(contains(proc.output, "--output /proc/x.png: cannot write in the folder /proc"))
        << proc.output;

    // A folder that goes away during a live session: its output fails, the other is written.
    auto args = sceneArgs(0);
    args.insert(args.end(),
                {"--local-clients", "1", "--control", "127.0.0.1:0", "--output",
                 (dir / "gone" / "a.png").string(), "--output", (dir / "good.png").string()});
    const fs::path log = dir / "gone.log";
    const pid_t master = spawnProcess(masterCommand(args), log);
    const std::string port = waitForControlPort(log, master);
    ASSERT_FALSE(port.empty()) << readFile(log);
    ASSERT_FALSE(waitForLine(log, std::regex(R"(frame +1:)"), master).empty()) << readFile(log);
    fs::remove_all(dir / "gone");
    std::ofstream(dir / "gone") << "a file where the folder was\n";
    ASSERT_EQ(runCtl(dir / "stop.log", port, {"stop"}).exitCode, 0);
    EXPECT_EQ(waitProcess(master, 120), 1) << readFile(log);
    EXPECT_TRUE(contains(readFile(log), "--output " + (dir / "gone" / "a.png").string()))
        << readFile(log);
    EXPECT_TRUE(fs::exists(dir / "good.png")) << readFile(log);
    fs::remove_all(dir);
}

// Items 5 and 6: statistics hold numbers as numbers and every setting; the log names the mode.
TEST(CommandLine, StatsRecordEverySettingAndTheLogNamesTheGiMode) {
    const fs::path dir = scratchDir("stats");
    const ProcessResult r =
        runMaster(dir / "run.log", 2,
                  {"--gi", "photonmap", "--seed", "7", "--stats-json", (dir / "s.json").string(),
                   "--output", (dir / "o.exr").string()});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "GI mode photonmap")) << r.output;
    std::ifstream in(dir / "s.json");
    const nlohmann::json session = nlohmann::json::parse(in)["session"];
    EXPECT_TRUE(session["width"].is_number_integer()) << session.dump();
    EXPECT_EQ(session["width"], 160);
    EXPECT_EQ(session["height"], 120);
    EXPECT_EQ(session["gi"], "photonmap");
    EXPECT_EQ(session["seed"], 7);
    EXPECT_EQ(session["frames"], 2);
    EXPECT_EQ(session["render"]["gi"], "photonmap");
    EXPECT_EQ(session["render"]["interleave"], nlohmann::json::array({3, 3}));
    EXPECT_EQ(session["render"]["direct_samples"], 4);
    fs::remove_all(dir);
}

// Item 7: a scene without a light is warned about; --headlight lights it.
TEST(CommandLine, ASceneWithoutLightIsWarnedAboutAndAHeadlightLightsIt) {
    const fs::path dir = scratchDir("dark");
    std::ofstream(dir / "floor.obj") << "v -1 0 -1\nv 1 0 -1\nv 0 0 1\nf 1 3 2\n";
    std::ofstream(dir / "dark.json")
        << R"({"camera": {"position": [0, 2, 3], "look_at": [0, 0, 0], "up": [0, 1, 0],
                          "fov_y": 45},
              "image": {"width": 32, "height": 24},
              "meshes": [{"file": "floor.obj"}], "lights": []})";
    const std::vector<std::string> base = {
        "--scene", (dir / "dark.json").string(), "--local-clients", "1", "--listen", "127.0.0.1:0"};
    auto dark = base;
    dark.insert(dark.end(), {"--output", (dir / "dark.exr").string()});
    const ProcessResult d = runProcess(masterCommand(dark), dir / "dark.log");
    ASSERT_EQ(d.exitCode, 0) << d.output;
    EXPECT_TRUE(contains(d.output, "has no light")) << d.output;
    EXPECT_TRUE(contains(d.output, "--headlight")) << d.output;
    EXPECT_EQ(meanLuminance(readImage(dir / "dark.exr")), 0.0);

    auto lit = base;
    lit.insert(lit.end(), {"--headlight", "--output", (dir / "lit.exr").string()});
    const ProcessResult l = runProcess(masterCommand(lit), dir / "lit.log");
    ASSERT_EQ(l.exitCode, 0) << l.output;
    EXPECT_TRUE(contains(l.output, "a headlight at the camera lights the scene (--headlight)"))
        << l.output;
    EXPECT_FALSE(contains(l.output, "has no light")) << l.output;
    EXPECT_GT(meanLuminance(readImage(dir / "lit.exr")), 1e-3);
    fs::remove_all(dir);
}

// Item 8: --animation without --frames renders the whole animation.
TEST(CommandLine, AnAnimationWithoutFramesRendersToItsLastKeyframe) {
    const fs::path dir = scratchDir("anim");
    std::ofstream(dir / "a.json") << R"({"objects": {"glass_ball": [
        {"frame": 0, "translate": [0.42, 0.36, 0.3]},
        {"frame": 3, "translate": [0.2, 0.36, 0.3]}]}})";
    auto args = sceneArgs(1);
    args.erase(args.begin() + 6, args.begin() + 8);  // its --frames
    args.insert(args.end(),
                {"--local-clients", "1", "--animation", (dir / "a.json").string(), "--stats-json",
                 (dir / "s.json").string(), "--output", (dir / "o.exr").string()});
    const ProcessResult r = runProcess(masterCommand(args), dir / "all.log");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "rendering its 4 frames")) << r.output;
    std::ifstream in(dir / "s.json");
    EXPECT_EQ(nlohmann::json::parse(in)["frames"].size(), 4u);

    const ProcessResult shorter =
        runMaster(dir / "short.log", 2,
                  {"--animation", (dir / "a.json").string(), "--output", (dir / "o.exr").string()});
    ASSERT_EQ(shorter.exitCode, 0) << shorter.output;
    EXPECT_TRUE(contains(shorter.output, "--frames 2 stops before the end of --animation"))
        << shorter.output;
    fs::remove_all(dir);
}

// Items 12 and 18: errors name the flag; integer options are INT and refuse fractions alike.
TEST(CommandLine, ErrorsNameTheFlagAndIntegerOptionsAreWholeNumbers) {
    const fs::path dir = scratchDir("flags");
    const ProcessResult spp = runMaster(dir / "spp.log", 1, {"--integrator", "path", "--spp", "0"});
    EXPECT_EQ(spp.exitCode, 2) << spp.output;
    EXPECT_TRUE(contains(spp.output, "--spp: must be in [1, 65536], got 0")) << spp.output;
    EXPECT_FALSE(contains(spp.output, "/render/")) << spp.output;

    int code = -1;
    for (const std::vector<std::string>& bad : {std::vector<std::string>{"--spp", "2.5"},
                                                {"--direct-samples", "1.5"},
                                                {"--max-clients", "2.5"},
                                                {"--seed", "1.5"}}) {
        const ProcessResult r = runMaster(dir / "bad.log", 1, bad);
        EXPECT_NE(r.exitCode, 0) << r.output;
        if (code < 0) code = r.exitCode;
        EXPECT_EQ(r.exitCode, code) << bad[0] << ": one exit code for every such mistake";
        EXPECT_TRUE(contains(r.output, bad[0] + ": expected a whole number")) << r.output;
        EXPECT_TRUE(contains(r.output, "got '" + bad[1] + "'")) << r.output;
    }
    const ProcessResult help = runProcess(masterCommand({"--help"}), dir / "help.log");
    for (const char* option : {"--seed INT", "--tile-size INT", "--direct-samples INT", "--spp INT",
                               "--clamp-distance FLOAT"})
        EXPECT_TRUE(contains(help.output, option)) << option << "\n" << help.output;
    fs::remove_all(dir);
}

// Item 13: options that would do nothing are warned about.
TEST(CommandLine, OptionsThatDoNothingAreWarnedAbout) {
    const fs::path dir = scratchDir("useless");
    const ProcessResult r = runMaster(
        dir / "run.log", 1, {"--spp", "4", "--sequence-frames", "1", "--spt-groups", "4"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const char* warning :
         {"--spp sets the path tracer's samples; IGI ignores it",
          "--sequence-frames does nothing without --output-sequence",
          "--spt-groups does nothing with --gi igi", "no --output (nor --output-sequence)"})
        EXPECT_TRUE(contains(r.output, warning)) << warning << "\n" << r.output;
    fs::remove_all(dir);
}

// Item 14: a scene warning is said once, by the master, not again by each local client.
TEST(CommandLine, ASceneWarningIsSaidOnceNotOncePerLocalClient) {
    const fs::path dir = scratchDir("warn-once");
    std::ofstream(dir / "w.obj") << "mtllib w.mtl\nv -1 0 -1\nv 1 0 -1\nv 0 0 1\n"
                                    "usemtl bright\nf 1 3 2\n";
    std::ofstream(dir / "w.mtl")
        << "newmtl bright\nillum 2\nKd 0.9 0.9 0.9\nKs 0.5 0.5 0.5\nNs 10\n";
    std::ofstream(dir / "w.json")
        << R"({"camera": {"position": [0, 2, 3], "look_at": [0, 0, 0], "up": [0, 1, 0],
                          "fov_y": 45},
              "image": {"width": 32, "height": 24}, "meshes": [{"file": "w.obj"}],
              "lights": [{"type": "point", "position": [0, 1, 0], "intensity": [1, 1, 1]}]})";
    const ProcessResult r =
        runProcess(masterCommand({"--scene", (dir / "w.json").string(), "--local-clients", "2",
                                  "--listen", "127.0.0.1:0", "--output", (dir / "o.exr").string()}),
                   dir / "run.log");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::size_t said = 0;
    for (std::size_t at = r.output.find("scaled down"); at != std::string::npos;
         at = r.output.find("scaled down", at + 1))
        ++said;
    EXPECT_EQ(said, 1u) << r.output;
    fs::remove_all(dir);
}

// Item 21: --width alone keeps the scene's aspect ratio (640 x 480).
TEST(CommandLine, WidthAloneKeepsTheScenesAspectRatio) {
    const fs::path dir = scratchDir("aspect");
    const ProcessResult r =
        runProcess(masterCommand({"--scene", (sourceDir() / "scenes/cornell/cornell.json").string(),
                                  "--width", "80", "--local-clients", "1", "--listen",
                                  "127.0.0.1:0", "--output", (dir / "o.exr").string()}),
                   dir / "run.log");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const Image image = readImage(dir / "o.exr");
    EXPECT_EQ(image.width, 80);
    EXPECT_EQ(image.height, 60);
    fs::remove_all(dir);
}

// Item 11: a port that cannot be used names the flag and the address.
TEST(CommandLine, PortErrorsNameTheFlagAndTheAddress) {
    const fs::path dir = scratchDir("ports");
    const int fd = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t size = sizeof address;
    ASSERT_EQ(bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
    ASSERT_EQ(listen(fd, 1), 0);
    ASSERT_EQ(getsockname(fd, reinterpret_cast<sockaddr*>(&address), &size), 0);
    const std::string busy = std::to_string(ntohs(address.sin_port));
    for (const char* flag : {"--listen", "--control"}) {
        auto args = sceneArgs(1);
        if (std::string(flag) == "--listen") args.resize(args.size() - 4);  // its own --listen
        args.insert(args.end(), {"--local-clients", "1", flag, "127.0.0.1:" + busy});
        const ProcessResult r = runProcess(masterCommand(args), dir / "busy.log", 60);
        EXPECT_NE(r.exitCode, 0) << r.output;
        EXPECT_TRUE(contains(r.output, std::string(flag) + " 127.0.0.1:" + busy +
                                           ": cannot listen there: Address already in use"))
            << r.output;
    }
    close(fd);
    const std::string closed = std::to_string(freePort());
    const ProcessResult ctl = runCtl(dir / "ctl.log", closed, {"status"});
    EXPECT_EQ(ctl.exitCode, 2) << ctl.output;
    EXPECT_TRUE(contains(ctl.output, "--connect 127.0.0.1:" + closed + ": cannot reach the master"))
        << ctl.output;
    fs::remove_all(dir);
}

// Item 9: a live session logs a frame line a second, not one a frame, on a terminal and in a
// log file alike.
TEST(CommandLine, ALiveSessionLogsAFrameLineASecond) {
    for (const bool terminal : {true, false}) {
        SCOPED_TRACE(terminal ? "on a terminal" : "in a log file");
        const fs::path dir = scratchDir("live-log");
        const std::string port = std::to_string(freePort());
        auto args = sceneArgs(0, "127.0.0.1:0", "info");
        args.insert(args.end(), {"--local-clients", "1", "--control", "127.0.0.1:" + port});
        std::vector<std::string> command = masterCommand(args);
        if (terminal) {
            // util-linux's script runs the master on a pseudo-terminal (as
            // tests/Progress_test.cpp).
            std::string line;
            for (const std::string& a : command) line += (line.empty() ? "'" : " '") + a + "'";
            command = {"/usr/bin/script", "-qec", line, (dir / "typescript").string()};
        }
        const fs::path log = dir / "master.log";
        const pid_t master = spawnProcess(command, log);
        ASSERT_FALSE(waitForLine(log, std::regex(R"(frame +0:)"), master).empty()) << readFile(log);
        std::this_thread::sleep_for(std::chrono::seconds(3));
        const nlohmann::json stop = replyOf(runCtl(dir / "stop.log", port, {"stop"}));
        ASSERT_TRUE(stop.value("ok", false)) << stop.dump();
        ASSERT_EQ(waitProcess(master, 120), 0) << readFile(log);
        const std::string text = readFile(log);
        const std::regex frameLine(R"(frame +\d+:)");
        const auto lines = std::distance(std::sregex_iterator(text.begin(), text.end(), frameLine),
                                         std::sregex_iterator());
        const int frames = stop["frames_done"].get<int>();
        EXPECT_GT(frames, 10) << "too slow to tell:\n" << text;
        EXPECT_LE(lines, 6) << frames << " frames\n" << text;
        EXPECT_TRUE(contains(text, "frames since the last line)")) << text;
        fs::remove_all(dir);
    }
}

// Item 14: under the progress line, local clients' info lines do not cut into it.
TEST(CommandLine, LocalClientsKeepQuietUnderTheProgressLine) {
    const fs::path dir = scratchDir("quiet-tty");
    auto args = sceneArgs(3);
    args.insert(args.end(), {"--local-clients", "2"});
    std::string line;
    for (const std::string& a : masterCommand(args)) line += (line.empty() ? "'" : " '") + a + "'";
    const ProcessResult tty = runProcess(
        {"/usr/bin/script", "-qec", line, (dir / "typescript").string()}, dir / "tty.log");
    ASSERT_EQ(tty.exitCode, 0) << tty.output;
    EXPECT_TRUE(contains(tty.output, "frame 3/3 [")) << tty.output;
    EXPECT_FALSE(std::regex_search(tty.output, std::regex(R"(\[client \d+\] \[info\])")))
        << tty.output;
    fs::remove_all(dir);
}

// Items 4, 9 (commands and snapshots logged), 10, 15 and 19: a live session under igi-ctl.
TEST(CommandLine, IgiCtlGetsRatesAtOnceWholePathsAndWarningsAndTheLogSaysWhatItDid) {
    const fs::path dir = scratchDir("ctl");
    auto args = sceneArgs(0);
    args.insert(args.end(), {"--local-clients", "1", "--control", "127.0.0.1:0", "--output",
                             (dir / "final.exr").string()});
    const fs::path log = dir / "master.log";
    const pid_t master = spawnProcess(masterCommand(args), log);
    const std::string port = waitForControlPort(log, master);
    ASSERT_FALSE(port.empty()) << readFile(log);
    ASSERT_FALSE(waitForLine(log, std::regex(R"(frame +3:)"), master).empty()) << readFile(log);

    // The session's first status already has the clients' rates.
    const nlohmann::json status = replyOf(runCtl(dir / "status.log", port, {"status"}));
    ASSERT_TRUE(status.value("ok", false)) << status.dump();
    ASSERT_EQ(status["client_list"].size(), 1u) << status.dump();
    EXPECT_GT(status["client_list"][0]["mrays_per_s"].get<double>(), 0) << status.dump();
    EXPECT_GT(status["client_list"][0]["tiles_per_s"].get<double>(), 0) << status.dump();
    EXPECT_GT(status["wire_mb_per_s"].get<double>(), 0) << status.dump();

    // A relative snapshot path is answered with the whole path written; none is fine too.
    const std::string relative = "igi-e2e-snapshot-" + std::to_string(getpid()) + "/now.png";
    const nlohmann::json snap = replyOf(runCtl(dir / "snap.log", port, {"snapshot", relative}));
    ASSERT_TRUE(snap.value("ok", false)) << snap.dump();
    const fs::path written = snap["path"].get<std::string>();
    EXPECT_TRUE(written.is_absolute()) << written;
    EXPECT_EQ(written, fs::absolute(relative).lexically_normal());
    EXPECT_TRUE(fs::exists(written)) << written;
    fs::remove_all(fs::path(relative).parent_path());
    const nlohmann::json unnamed = replyOf(runCtl(dir / "snap2.log", port, {"snapshot"}));
    ASSERT_TRUE(unnamed.value("ok", false)) << unnamed.dump();
    EXPECT_EQ(fs::path(unnamed["path"].get<std::string>()).parent_path(), dir);

    // A change the master had to alter says so in the reply.
    const nlohmann::json scaled = replyOf(runCtl(
        dir / "material.log", port, {"material", "red", "--type", "mirror", "--specular", "0.9"}));
    ASSERT_TRUE(scaled.value("ok", false)) << scaled.dump();
    ASSERT_TRUE(scaled.contains("warnings")) << scaled.dump();
    EXPECT_TRUE(contains(scaled["warnings"][0].get<std::string>(), "scaled down"));
    for (const std::vector<std::string>& query :
         {std::vector<std::string>{"scene"}, {"pick", "80", "60"}, {"exposure", "1"}}) {
        const nlohmann::json reply = replyOf(runCtl(dir / "query.log", port, query));
        EXPECT_TRUE(reply.value("ok", false)) << query[0] << ": " << reply.dump();
    }

    ASSERT_EQ(runCtl(dir / "stop.log", port, {"stop"}).exitCode, 0);
    ASSERT_EQ(waitProcess(master, 120), 0) << readFile(log);
    const std::string text = readFile(log);
    EXPECT_TRUE(contains(text, "snapshot of frame")) << text;
    EXPECT_TRUE(contains(text, "igi-ctl command at frame")) << text;
    EXPECT_TRUE(contains(text, R"("cmd":"stop")")) << text;

    const ProcessResult help =
        runProcess({(binDir() / "igi-ctl").string(), "light", "--help"}, dir / "help.log", 30);
    EXPECT_TRUE(contains(help.output, "--on true|false")) << help.output;
    EXPECT_TRUE(contains(help.output, "--position X Y Z")) << help.output;
    const ProcessResult version =
        runProcess({(binDir() / "igi-ctl").string(), "--version"}, dir / "version.log", 30);
    EXPECT_EQ(version.exitCode, 0) << version.output;
    EXPECT_TRUE(contains(version.output, igi::buildId())) << version.output;
    fs::remove_all(dir);
}

}  // namespace
}  // namespace igi
