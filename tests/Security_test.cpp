// Who may join, and what hostile peers get: clients without the cluster secret, impostor
// masters, garbage and out-of-order messages, version and build mismatches, a full master.
// Real processes on loopback; raw sockets (RawPeer.h) play the hostile side.
#include <filesystem>
#include <fstream>
#include <regex>

#include <gtest/gtest.h>

#include "BuildId.h"
#include "RawPeer.h"
#include "Session.h"

namespace igi {
namespace {

using namespace igi::testing;
namespace fs = std::filesystem;

constexpr std::uint16_t kOtherVersion = proto::kVersion + 1;

fs::path writeSecret(const fs::path& dir, const std::string& name, const std::string& secret) {
    std::ofstream(dir / name) << secret << "\n";
    return dir / name;
}

/// A connection to the master that has read its Challenge: the state a hostile peer starts in.
RawPeer challenged(int port) {
    RawPeer peer = RawPeer::connectTo(port);
    if (!peer.valid()) return peer;
    const auto first = peer.receive();
    if (!first || !std::holds_alternative<proto::Challenge>(*first)) return RawPeer();
    return peer;
}

TEST(Security, PeersWithoutTheSecretGetNothingAndTheSessionGoesOn) {
    const fs::path dir = scratchDir("nosecret");
    const fs::path secret = writeSecret(dir, "secret", "the cluster's own shared secret");
    const fs::path wrong = writeSecret(dir, "wrong", "a guess at the cluster's secret");
    OpenSession session(dir, {"--local-clients", "1", "--secret-file", secret.string(),
                              "--handshake-timeout", "1"});
    ASSERT_TRUE(session.started()) << readFile(session.log);
    ASSERT_TRUE(session.waitFrames(2)) << readFile(session.log);
    const std::string address = "127.0.0.1:" + session.port;

    // A client with the wrong secret, and one that offers no proof at all, are refused: exit
    // code 3, no retry, and no scene ever reached them.
    for (const auto& [name, how] : std::vector<std::pair<std::string, std::vector<std::string>>>{
             {"wrong", {"--secret-file", wrong.string()}}, {"none", {"--insecure"}}}) {
        auto args = std::vector<std::string>{"--connect", address, "--reconnect-seconds", "60"};
        args.insert(args.end(), how.begin(), how.end());
        const ProcessResult r = runProcess(clientCommand(args), dir / (name + ".log"), 60);
        EXPECT_EQ(r.exitCode, 3) << r.output;
        EXPECT_NE(r.output.find("secret"), std::string::npos) << r.output;
        EXPECT_EQ(r.output.find("ready"), std::string::npos) << "got a scene:\n" << r.output;
    }

    const int port = std::stoi(session.port);
    {  // Garbage where a Hello belongs.
        RawPeer peer = challenged(port);
        ASSERT_TRUE(peer.valid());
        peer.send(std::vector<std::uint8_t>(100, 0xAB));
        EXPECT_TRUE(peer.closedByPeer());
    }
    {  // A tile result, unasked, before any handshake: it must not reach a frame.
        RawPeer peer = challenged(port);
        ASSERT_TRUE(peer.valid());
        proto::TileResult forged;
        forged.tileId = 0;
        forged.channels.resize(9, kIrradiance);
        for (auto& p : forged.channels.irradiance) p = glm::vec3(1e6f);
        peer.send(forged);
        const auto answer = peer.receive();
        ASSERT_TRUE(answer && std::holds_alternative<proto::Error>(*answer));
        EXPECT_NE(std::get<proto::Error>(*answer).reason.find("before the scene was ready"),
                  std::string::npos);
        EXPECT_TRUE(peer.closedByPeer());
    }
    {  // Another protocol version: refused, and the master's log says which versions met.
        RawPeer peer = challenged(port);
        ASSERT_TRUE(peer.valid());
        proto::Hello hello;
        hello.buildId = igi::buildId();
        auto bytes = proto::encodeMessage(hello, 0, 0);
        // The header's version, after the 4-byte magic: the next one, which no build speaks yet.
        bytes[4] = std::uint8_t(kOtherVersion & 0xFF), bytes[5] = std::uint8_t(kOtherVersion >> 8);
        peer.send(bytes);
        EXPECT_TRUE(peer.closedByPeer());
    }
    {  // Another build: refused with both build identities named.
        RawPeer peer = challenged(port);
        ASSERT_TRUE(peer.valid());
        proto::Hello hello;
        hello.buildId = "0.0-someone-elses-build";
        peer.send(hello);
        const auto answer = peer.receive();
        ASSERT_TRUE(answer && std::holds_alternative<proto::Error>(*answer));
        const std::string reason = std::get<proto::Error>(*answer).reason;
        EXPECT_NE(reason.find("0.0-someone-elses-build"), std::string::npos) << reason;
        EXPECT_NE(reason.find(igi::buildId()), std::string::npos) << reason;
    }
    {  // A peer that connects and never proves itself loses its slot.
        RawPeer idle = RawPeer::connectTo(port);
        ASSERT_TRUE(idle.valid());
        EXPECT_TRUE(idle.closedByPeer());
    }
    ASSERT_TRUE(session.waitFrames(2)) << readFile(session.log);

    const std::string log = readFile(session.log);
    EXPECT_NE(log.find("does not hold this cluster's secret"), std::string::npos) << log;
    EXPECT_NE(log.find("protocol version " + std::to_string(kOtherVersion)), std::string::npos)
        << log;
    EXPECT_NE(log.find("no valid Hello within 1 s"), std::string::npos) << log;
    const int frames = session.stop();
    ASSERT_GT(frames, 0) << readFile(session.log);
    expectSameAsUndisturbed(dir, frames);
    if (!HasFailure()) fs::remove_all(dir);
}

/// Plays a master up to its Welcome, for the client at `clientArgs`; returns the client's
/// exit code and log, and whether the client sent anything after the Welcome.
struct ImpostorRun {
    int exitCode = -1;
    std::string log;
    bool sentAfterWelcome = false;
};

ImpostorRun runAgainstImpostor(const fs::path& dir, const std::string& name,
                               const proto::Challenge& challenge,
                               const std::optional<proto::AuthBytes>& proof,
                               const std::vector<std::string>& clientArgs) {
    RawListener listener;
    auto args = std::vector<std::string>{
        "--connect", "127.0.0.1:" + std::to_string(listener.port()), "--reconnect-seconds", "0"};
    args.insert(args.end(), clientArgs.begin(), clientArgs.end());
    const fs::path log = dir / (name + ".log");
    const pid_t client = spawnProcess(clientCommand(args), log);
    ImpostorRun run;
    RawPeer peer = listener.accept();
    if (peer.valid()) {
        peer.send(challenge);
        const auto hello = peer.receive();
        if (hello && std::holds_alternative<proto::Hello>(*hello)) {
            peer.send(proto::Welcome{1, 42, proof});
            // A client that trusted the Welcome would now wait for the scene, not close.
            const auto next = peer.receive(5);
            run.sentAfterWelcome = next && !std::holds_alternative<proto::Error>(*next);
        }
    }
    run.exitCode = waitProcess(client, 30);
    run.log = readFile(log);
    return run;
}

TEST(Security, AClientTakesNothingFromAMasterThatCannotProveTheSecret) {
    const fs::path dir = scratchDir("impostor");
    const fs::path secret = writeSecret(dir, "secret", "the cluster's own shared secret");
    proto::Challenge challenge;
    challenge.buildId = igi::buildId();
    challenge.nonce.fill(3);

    proto::AuthBytes forged;
    forged.fill(0x5A);
    for (const auto& [name, proof] :
         std::vector<std::pair<std::string, std::optional<proto::AuthBytes>>>{
             {"forged", forged}, {"missing", std::nullopt}}) {
        const ImpostorRun run =
            runAgainstImpostor(dir, name, challenge, proof, {"--secret-file", secret.string()});
        EXPECT_EQ(run.exitCode, 3) << run.log;
        EXPECT_FALSE(run.sentAfterWelcome) << run.log;
        EXPECT_NE(run.log.find("could not prove"), std::string::npos) << run.log;
    }

    // A master of another build: the client refuses it, naming both builds.
    proto::Challenge other = challenge;
    other.buildId = "0.0-someone-elses-build";
    const ImpostorRun run =
        runAgainstImpostor(dir, "build", other, std::nullopt, {"--secret-file", secret.string()});
    EXPECT_EQ(run.exitCode, 3) << run.log;
    EXPECT_NE(run.log.find("0.0-someone-elses-build"), std::string::npos) << run.log;
    EXPECT_NE(run.log.find(igi::buildId()), std::string::npos) << run.log;
    if (!HasFailure()) fs::remove_all(dir);
}

TEST(Security, AFullMasterTurnsNewcomersAwayAndInsecureAndControlStayOnLoopback) {
    const fs::path dir = scratchDir("limits");
    OpenSession session(dir, {"--local-clients", "1", "--max-clients", "1"});
    ASSERT_TRUE(session.started()) << readFile(session.log);
    ASSERT_TRUE(session.waitFrames(1)) << readFile(session.log);
    RawPeer extra = RawPeer::connectTo(std::stoi(session.port));
    ASSERT_TRUE(extra.valid());
    const auto answer = extra.receive();
    ASSERT_TRUE(answer && std::holds_alternative<proto::Error>(*answer));
    EXPECT_NE(std::get<proto::Error>(*answer).reason.find("full"), std::string::npos);
    EXPECT_TRUE(extra.closedByPeer());
    EXPECT_GT(session.stop(), 0) << readFile(session.log);

    auto args = sceneArgs(1, "0.0.0.0:0");
    args.insert(args.end(), {"--insecure", "--local-clients", "1"});
    const ProcessResult r = runProcess(masterCommand(args), dir / "insecure.log", 60);
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("--insecure is for loopback only"), std::string::npos) << r.output;

    // The control port has no authentication of its own: never off this machine.
    auto controlled = sceneArgs(1);
    controlled.insert(controlled.end(), {"--control", "0.0.0.0:0", "--local-clients", "1"});
    const ProcessResult c = runProcess(masterCommand(controlled), dir / "control.log", 60);
    EXPECT_NE(c.exitCode, 0);
    EXPECT_NE(c.output.find("loopback only"), std::string::npos) << c.output;
    if (!HasFailure()) fs::remove_all(dir);
}

}  // namespace
}  // namespace igi
