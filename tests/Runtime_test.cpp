// The distributed runtime under change: clients killed mid-frame, clients joining mid-session,
// different numbers of clients. Real processes on loopback; images compared bit for bit.
#include <csignal>
#include <filesystem>
#include <fstream>
#include <regex>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "Session.h"

namespace igi {
namespace {

using namespace igi::testing;
namespace fs = std::filesystem;

TEST(Runtime, OneTwoAndFourClientsGiveTheSamePixels) {
    const fs::path dir = scratchDir("clients");
    for (int clients : {1, 2, 4}) {
        auto args = sceneArgs(3);
        const std::string name = "c" + std::to_string(clients);
        args.insert(args.end(), {"--local-clients", std::to_string(clients), "--output",
                                 (dir / (name + ".exr")).string()});
        const ProcessResult r = runProcess(masterCommand(args), dir / (name + ".log"));
        ASSERT_EQ(r.exitCode, 0) << r.output;
    }
    expectSameImage(dir / "c1.exr", dir / "c2.exr");
    expectSameImage(dir / "c1.exr", dir / "c4.exr");
    fs::remove_all(dir);
}

TEST(Runtime, AClientKilledMidFrameLosesNothing) {
    const fs::path dir = scratchDir("kill");
    const int frames = 24;
    auto reference = sceneArgs(frames);
    reference.insert(reference.end(),
                     {"--local-clients", "1", "--output", (dir / "reference.exr").string()});
    ASSERT_EQ(runProcess(masterCommand(reference), dir / "reference.log").exitCode, 0);

    auto args = sceneArgs(frames);
    args.insert(args.end(), {"--local-clients", "2", "--output", (dir / "killed.exr").string()});
    const fs::path log = dir / "killed.log";
    const pid_t master = spawnProcess(masterCommand(args), log);
    ASSERT_GT(master, 0);
    const auto started =
        waitForLine(log, std::regex(R"(started local client 2 \(pid (\d+)\))"), master);
    ASSERT_FALSE(started.empty()) << readFile(log);
    const pid_t victim = std::stoi(started[1].str());
    // Once frames flow, kill the second client without warning, in the middle of its tiles.
    ASSERT_FALSE(waitForLine(log, std::regex(R"(frame +2:)"), master).empty()) << readFile(log);
    ASSERT_EQ(kill(victim, SIGKILL), 0);
    ASSERT_EQ(waitProcess(master, 300), 0) << readFile(log);
    const std::string text = readFile(log);
    EXPECT_NE(text.find("of its tiles go to others"), std::string::npos)
        << "the kill came too late:\n"
        << text;
    expectSameImage(dir / "killed.exr", dir / "reference.exr");
    fs::remove_all(dir);
}

TEST(Runtime, AClientJoiningMidSessionGetsWorkInTheNextFrames) {
    const fs::path dir = scratchDir("join");
    // Until stopped: however slow the machine, the session outlives the join.
    // A client from outside the master's own process tree: it must hold the cluster secret.
    const fs::path secret = dir / "secret";
    std::ofstream(secret) << "the render cluster's shared secret\n";
    auto args = sceneArgs(0);
    args.insert(args.end(), {"--local-clients", "1", "--output", (dir / "joined.exr").string(),
                             "--stats-json", (dir / "stats.json").string(), "--control",
                             "127.0.0.1:0", "--secret-file", secret.string()});
    const fs::path log = dir / "master.log";
    const pid_t master = spawnProcess(masterCommand(args), log);
    ASSERT_GT(master, 0);
    const auto listening =
        waitForLine(log, std::regex(R"(listening on 127\.0\.0\.1:(\d+))"), master);
    ASSERT_FALSE(listening.empty()) << readFile(log);
    const std::string port = listening[1].str();
    const std::string controlPort = waitForControlPort(log, master);
    ASSERT_FALSE(controlPort.empty()) << readFile(log);
    ASSERT_FALSE(waitForLine(log, std::regex(R"(frame +3:)"), master).empty()) << readFile(log);

    const pid_t joiner =
        spawnProcess({(binDir() / "igi-client").string(), "--connect", "127.0.0.1:" + port,
                      "--threads", "1", "--secret-file", secret.string()},
                     dir / "joiner.log");
    ASSERT_GT(joiner, 0);
    const auto ready = waitForLine(log, std::regex(R"(client 2 \(.*\) is ready)"), master);
    ASSERT_FALSE(ready.empty()) << "the joiner was never ready:\n"
                                << readFile(log) << readFile(dir / "joiner.log");
    // The last frame finished before the joiner was ready.
    const std::string text = readFile(log);
    const std::string before = text.substr(0, text.find("client 2 ("));
    const std::regex frameLine(R"(frame +(\d+):)");
    std::uint32_t lastFrame = 0;
    for (std::sregex_iterator it(before.begin(), before.end(), frameLine), end; it != end; ++it)
        lastFrame = std::uint32_t(std::stoul((*it)[1].str()));
    // Let a few more frames go by, then stop the session.
    const std::regex later("frame +" + std::to_string(lastFrame + 6) + ":");
    ASSERT_FALSE(waitForLine(log, later, master).empty()) << readFile(log);
    const ProcessResult stop = runCtl(dir / "ctl.log", controlPort, {"stop"});
    ASSERT_EQ(stop.exitCode, 0) << stop.output;
    ASSERT_EQ(waitProcess(master, 300), 0) << readFile(log);
    EXPECT_EQ(waitProcess(joiner, 30), 0) << readFile(dir / "joiner.log");

    std::ifstream statsFile(dir / "stats.json");
    const auto stats = nlohmann::json::parse(statsFile);
    ASSERT_EQ(stats["clients"].size(), 2u);
    const auto& joined = stats["clients"][1];
    ASSERT_GT(joined["tiles"].get<int>(), 0) << "the joiner never got a tile";
    // Frames in flight when it joined: the last finished one + 1 to + 4 (up to four are open,
    // master/Master.cpp); it must be given tiles of those or of the next one opened.
    EXPECT_LE(joined["first_frame"].get<std::int64_t>(), std::int64_t(lastFrame) + 5)
        << "joined after frame " << lastFrame;
    fs::remove_all(dir);
}

}  // namespace
}  // namespace igi

namespace igi {
namespace {

TEST(Runtime, WhenEveryClientIsGoneTheMasterGivesUpClearlyInsteadOfHanging) {
    const fs::path dir = scratchDir("allgone");
    auto args = sceneArgs(100000);
    args.insert(args.end(), {"--local-clients", "1", "--wait-seconds", "2"});
    const fs::path log = dir / "master.log";
    const pid_t master = spawnProcess(masterCommand(args), log);
    const auto started =
        waitForLine(log, std::regex(R"(started local client 1 \(pid (\d+)\))"), master);
    ASSERT_FALSE(started.empty()) << readFile(log);
    ASSERT_FALSE(waitForLine(log, std::regex(R"(frame +1:)"), master).empty()) << readFile(log);
    kill(std::stoi(started[1].str()), SIGKILL);
    EXPECT_EQ(waitProcess(master, 60), 4) << readFile(log);
    EXPECT_NE(readFile(log).find("every client left"), std::string::npos) << readFile(log);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace igi
