// Faults while a session runs: a client stopped and resumed, a client stopped until the master
// gives up on it, a connection cut, a master restarted under its clients. Real processes on
// loopback; each run's image must equal, bit for bit, an undisturbed run of as many frames.
#include <csignal>
#include <filesystem>
#include <fstream>
#include <regex>

#include <gtest/gtest.h>

#include "Session.h"
#include "TcpProxy.h"

namespace igi {
namespace {

using namespace igi::testing;
namespace fs = std::filesystem;

pid_t localClientPid(const OpenSession& s, int index) {
    const auto started = waitForLine(
        s.log, std::regex("started local client " + std::to_string(index) + R"( \(pid (\d+)\))"),
        s.master);
    return started.empty() ? -1 : std::stoi(started[1].str());
}

TEST(Faults, AClientStoppedAndResumedHoldsNothingBackAndLosesNothing) {
    const fs::path dir = scratchDir("sigstop");
    OpenSession session(dir, {"--local-clients", "2"});
    ASSERT_TRUE(session.started()) << readFile(session.log);
    const pid_t victim = localClientPid(session, 2);
    ASSERT_GT(victim, 0) << readFile(session.log);
    ASSERT_TRUE(session.waitFrames(3)) << readFile(session.log);

    // Stopped with tiles in hand, for less than the read timeout: the master must not wait for
    // it (the other client takes duplicates of its late tiles), and its stale results, sent when
    // it resumes, must not disturb later frames.
    ASSERT_EQ(kill(victim, SIGSTOP), 0);
    const int before = session.lastFrame();
    const bool progressed = session.waitFrames(3);
    ASSERT_EQ(kill(victim, SIGCONT), 0);
    EXPECT_TRUE(progressed) << "frames stalled while a client was stopped:\n"
                            << readFile(session.log);
    EXPECT_GT(session.lastFrame(), before);
    ASSERT_TRUE(session.waitFrames(3)) << readFile(session.log);
    const int frames = session.stop();
    ASSERT_GT(frames, 0) << readFile(session.log);
    expectSameAsUndisturbed(dir, frames);
    if (!HasFailure()) fs::remove_all(dir);  // kept for a look when it failed
}

TEST(Faults, AClientStoppedPastTheReadTimeoutIsDroppedAndItsTilesGoToOthers) {
    const fs::path dir = scratchDir("silent");
    OpenSession session(dir, {"--local-clients", "2", "--read-timeout", "4"});
    ASSERT_TRUE(session.started()) << readFile(session.log);
    const pid_t victim = localClientPid(session, 2);
    ASSERT_GT(victim, 0) << readFile(session.log);
    ASSERT_TRUE(session.waitFrames(2)) << readFile(session.log);

    ASSERT_EQ(kill(victim, SIGSTOP), 0);
    const auto dropped = waitForLine(session.log, std::regex(R"(client \d+ left \(read timeout)"),
                                     session.master, 60);
    ASSERT_EQ(kill(victim, SIGCONT), 0);
    ASSERT_FALSE(dropped.empty()) << "the silent client was never dropped:\n"
                                  << readFile(session.log);
    ASSERT_TRUE(session.waitFrames(3)) << readFile(session.log);
    const int frames = session.stop();
    ASSERT_GT(frames, 0) << readFile(session.log);
    expectSameAsUndisturbed(dir, frames);
    if (!HasFailure()) fs::remove_all(dir);  // kept for a look when it failed
}

TEST(Faults, AClientWhoseConnectionIsCutComesBackAndNothingIsLost) {
    const fs::path dir = scratchDir("cut");
    const fs::path secret = dir / "secret";
    std::ofstream(secret) << "a secret shared by the master and the far client\n";
    OpenSession session(dir, {"--local-clients", "1", "--secret-file", secret.string()});
    ASSERT_TRUE(session.started()) << readFile(session.log);

    TcpProxy proxy(std::uint16_t(std::stoi(session.port)));
    const fs::path clientLog = dir / "far-client.log";
    const pid_t farClient = spawnProcess(
        clientCommand({"--connect", "127.0.0.1:" + std::to_string(proxy.port()), "--threads", "1",
                       "--secret-file", secret.string(), "--reconnect-seconds", "60"}),
        clientLog);
    ASSERT_GT(farClient, 0);
    // The master numbers clients as they connect: ask the far client which it is.
    const std::regex named(R"(the master calls this client (\d+))");
    const auto first = waitForLine(clientLog, named, farClient);
    ASSERT_FALSE(first.empty()) << readFile(clientLog);
    const std::string firstId = first[1].str();
    ASSERT_FALSE(waitForLine(session.log, std::regex("client " + firstId + R"( \(.*\) is ready)"),
                             session.master)
                     .empty())
        << readFile(session.log) << readFile(clientLog);
    ASSERT_TRUE(session.waitFrames(2)) << readFile(session.log);

    proxy.cut();
    ASSERT_FALSE(
        waitForLine(session.log, std::regex("client " + firstId + " left"), session.master).empty())
        << readFile(session.log);
    // It reconnects through the same relay, proves itself again and gets the scene again, under
    // a new number.
    const std::regex renamed(
        R"(the master calls this client (\d+)[^]*the master calls this client (\d+))");
    const auto second = waitForLine(clientLog, renamed, farClient);
    ASSERT_FALSE(second.empty()) << readFile(clientLog);
    const std::string secondId = second[2].str();
    ASSERT_FALSE(waitForLine(session.log, std::regex("client " + secondId + R"( \(.*\) is ready)"),
                             session.master)
                     .empty())
        << readFile(session.log) << readFile(clientLog);
    EXPECT_EQ(proxy.connectionsAccepted(), 2);
    ASSERT_TRUE(session.waitFrames(3)) << readFile(session.log);
    const int frames = session.stop();
    ASSERT_GT(frames, 0) << readFile(session.log);
    EXPECT_EQ(waitProcess(farClient, 30), 0) << readFile(clientLog);
    expectSameAsUndisturbed(dir, frames);
    if (!HasFailure()) fs::remove_all(dir);  // kept for a look when it failed
}

// A client that joins while another holds tiles of frames of older epochs than the newest (an
// animation makes every frame a new epoch) must be able to finish them when that client dies:
// it gets every epoch of the frames open. One tile per frame (no interleaving, a tile over the
// whole image): the stopped client holds tiles of two frames at least, whatever the timing.
TEST(Faults, AJoinerFinishesTheOlderFramesOfAClientThatDied) {
    const fs::path dir = scratchDir("join-old-epochs");
    const fs::path secret = dir / "secret", slide = dir / "slide.json";
    std::ofstream(secret) << "the render cluster's shared secret\n";
    std::ofstream(slide) << R"({"objects": {"mirror_box": [)"
                         << R"({"frame": 0, "translate": [-0.38, 0, -0.3]},)"
                         << R"({"frame": 5000, "translate": [0.3, 0, -0.3]}]}})";
    const std::vector<std::string> shape = {"--animation", slide.string(), "--interleave", "1x1",
                                            "--filter",    "1x1",          "--tile-size",  "256"};
    std::vector<std::string> extra = shape;
    extra.insert(extra.end(), {"--local-clients", "1", "--secret-file", secret.string()});
    OpenSession session(dir, extra);
    ASSERT_TRUE(session.started()) << readFile(session.log);
    const pid_t victim = localClientPid(session, 1);
    ASSERT_GT(victim, 0) << readFile(session.log);
    ASSERT_TRUE(session.waitFrames(3)) << readFile(session.log);

    ASSERT_EQ(kill(victim, SIGSTOP), 0);
    // Long enough for the master to read what it sent before the stop and to give it the
    // tiles it holds from then on; nothing finishes after that.
    std::this_thread::sleep_for(std::chrono::seconds(2));
    const int stalledAfter = session.lastFrame();
    const pid_t joiner = session.join(secret, 2);
    ASSERT_GT(joiner, 0) << readFile(session.log) << readFile(dir / "joiner.log");
    ASSERT_EQ(kill(victim, SIGKILL), 0);
    ASSERT_TRUE(session.waitFrames(3)) << "the frames the dead client held were never finished:\n"
                                       << readFile(session.log) << readFile(dir / "joiner.log");
    const int frames = session.stop();
    ASSERT_GT(frames, 0) << readFile(session.log);
    EXPECT_EQ(waitProcess(joiner, 30), 0) << readFile(dir / "joiner.log");
    std::ifstream statsFile(dir / "stats.json");
    const auto stats = nlohmann::json::parse(statsFile);
    ASSERT_EQ(stats["clients"].size(), 2u);
    EXPECT_EQ(stats["clients"][1]["first_frame"].get<std::int64_t>(), stalledAfter + 1)
        << "the joiner's first tile is of the oldest frame the stopped client held";
    expectSameAsUndisturbed(dir, frames, shape);
    if (!HasFailure()) fs::remove_all(dir);  // kept for a look when it failed
}

TEST(Faults, AMasterRestartedWhileItsClientsRunGetsThemBack) {
    const fs::path dir = scratchDir("restart");
    const fs::path secret = dir / "secret";
    std::ofstream(secret) << "a secret shared by both masters and the client\n";
    const int port = freePort();
    ASSERT_GT(port, 0);
    const std::string address = "127.0.0.1:" + std::to_string(port);
    const std::vector<std::string> remote = {"--clients", "1", "--secret-file", secret.string()};

    auto firstArgs = sceneArgs(0, address);
    firstArgs.insert(firstArgs.end(), remote.begin(), remote.end());
    const fs::path firstLog = dir / "first.log";
    const pid_t first = spawnProcess(masterCommand(firstArgs), firstLog);
    ASSERT_GT(first, 0);
    ASSERT_FALSE(waitForLine(firstLog, std::regex("listening on"), first).empty())
        << readFile(firstLog);
    const fs::path clientLog = dir / "client.log";
    const pid_t client =
        spawnProcess(clientCommand({"--connect", address, "--threads", "2", "--secret-file",
                                    secret.string(), "--reconnect-seconds", "120"}),
                     clientLog);
    ASSERT_GT(client, 0);
    ASSERT_FALSE(waitForLine(firstLog, std::regex(R"(frame +2:)"), first).empty())
        << readFile(firstLog) << readFile(clientLog);

    // The master dies without a word; a new one comes up on the same port.
    ASSERT_EQ(kill(first, SIGKILL), 0);
    waitProcess(first, 10);
    ASSERT_FALSE(waitForLine(clientLog, std::regex("lost the master"), client).empty())
        << readFile(clientLog);
    const int frames = 5;
    auto secondArgs = sceneArgs(frames, address);
    secondArgs.insert(secondArgs.end(), remote.begin(), remote.end());
    secondArgs.insert(secondArgs.end(), {"--output", (dir / "faulty.exr").string()});
    const ProcessResult second = runProcess(masterCommand(secondArgs), dir / "second.log");
    ASSERT_EQ(second.exitCode, 0) << second.output << readFile(clientLog);
    // The second master ended the session: the client ends cleanly.
    EXPECT_EQ(waitProcess(client, 30), 0) << readFile(clientLog);

    expectSameAsUndisturbed(dir, frames);
    if (!HasFailure()) fs::remove_all(dir);  // kept for a look when it failed
}

}  // namespace
}  // namespace igi
