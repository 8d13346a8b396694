#pragma once
// What the end-to-end tests of a running session share: the master's command line, waiting for
// a line in a log, comparing images bit for bit.

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "Process.h"
#include "image/ImageIO.h"
#include "math/Color.h"

namespace igi::testing {

inline std::vector<std::string> masterCommand(const std::vector<std::string>& args) {
    std::vector<std::string> command = {(binDir() / "igi-master").string()};
    command.insert(command.end(), args.begin(), args.end());
    return command;
}

inline std::vector<std::string> clientCommand(const std::vector<std::string>& args) {
    std::vector<std::string> command = {(binDir() / "igi-client").string()};
    command.insert(command.end(), args.begin(), args.end());
    return command;
}

/// The default scene, small, for `frames` frames (0: until stopped), any free port. A live
/// session logs a frame line a second at info level and every frame's line at debug: its tests
/// follow the frames, so it logs at debug unless `logLevel` says.
inline std::vector<std::string> sceneArgs(int frames, const std::string& listen = "127.0.0.1:0",
                                          std::string logLevel = "") {
    if (logLevel.empty()) logLevel = frames == 0 ? "debug" : "info";
    return {"--scene",     (sourceDir() / "scenes/cornell/cornell.json").string(),
            "--width",     "160",
            "--height",    "120",
            "--frames",    std::to_string(frames),
            "--listen",    listen,
            "--log-level", logLevel};
}

/// A JSON file (statistics, a status), or a discarded value if it does not parse.
inline nlohmann::json readJson(const std::filesystem::path& path) {
    std::ifstream in(path);
    return nlohmann::json::parse(in, nullptr, false);
}

inline bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

/// Runs the master on the default scene, small, with one local client, for `frames` frames and
/// the arguments `extra`, its output going to `log`.
inline ProcessResult runMaster(const std::filesystem::path& log, int frames,
                               const std::vector<std::string>& extra, double timeout = 300) {
    auto args = sceneArgs(frames);
    args.insert(args.end(), {"--local-clients", "1"});
    args.insert(args.end(), extra.begin(), extra.end());
    return runProcess(masterCommand(args), log, timeout);
}

/// Waits until `log` contains a match of `pattern` (or the process ended); returns the match
/// (empty if none). The match refers into a static copy of the log: use it before calling
/// again.
inline std::smatch waitForLine(const std::filesystem::path& log, const std::regex& pattern,
                               pid_t pid, double seconds = 60) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    static std::string text;
    while (std::chrono::steady_clock::now() < deadline) {
        text = readFile(log);
        std::smatch m;
        if (std::regex_search(text, m, pattern)) return m;
        if (!processRunning(pid)) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return {};
}

/// The highest frame number a master's log reports finished (-1: none).
inline int lastFrameIn(const std::filesystem::path& log) {
    const std::string text = readFile(log);
    static const std::regex frameLine(R"(frame +(\d+):)");
    int last = -1;
    for (std::sregex_iterator it(text.begin(), text.end(), frameLine), end; it != end; ++it)
        last = std::max(last, std::stoi((*it)[1].str()));
    return last;
}

/// Reads an image a test produced; a NaN or infinite pixel fails the test.
inline Image readFiniteImage(const std::filesystem::path& path) {
    Image image = readImage(path);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        if (!isFinite(image.pixels[i])) {
            ADD_FAILURE() << path << " has a NaN or infinite value at pixel " << i;
            break;
        }
    return image;
}

/// Both images exist, hold only finite values and are identical, pixel for pixel.
inline void expectSameImage(const std::filesystem::path& a, const std::filesystem::path& b) {
    const Image x = readImage(a), y = readImage(b);
    ASSERT_EQ(x.pixels.size(), y.pixels.size()) << a << " and " << b;
    ASSERT_GT(x.pixels.size(), 0u) << a;
    for (std::size_t i = 0; i < x.pixels.size(); ++i) {
        ASSERT_TRUE(isFinite(x.pixels[i])) << a << " has a NaN or infinite pixel " << i;
        ASSERT_EQ(x.pixels[i], y.pixels[i]) << a << " and " << b << " differ at pixel " << i;
    }
}

/// A loopback port that was free a moment ago, for a master that must listen on a known port
/// (one restarted on the same port).
inline int freePort() {
    const int fd = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t size = sizeof address;
    int port = -1;
    if (bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0 &&
        getsockname(fd, reinterpret_cast<sockaddr*>(&address), &size) == 0)
        port = ntohs(address.sin_port);
    close(fd);
    return port;
}

/// dir/faulty.exr equals the image of the same scene rendered undisturbed, by one local client,
/// for `frames` frames.
/// `extra`: the arguments of the disturbed session that shape its image (an animation, the
/// tiles).
inline void expectSameAsUndisturbed(const std::filesystem::path& dir, int frames,
                                    const std::vector<std::string>& extra = {}) {
    auto args = sceneArgs(frames);
    args.insert(args.end(),
                {"--local-clients", "1", "--output", (dir / "undisturbed.exr").string()});
    args.insert(args.end(), extra.begin(), extra.end());
    const ProcessResult r = runProcess(masterCommand(args), dir / "undisturbed.log");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    expectSameImage(dir / "faulty.exr", dir / "undisturbed.exr");
}

/// The control port of a master started with `--control 127.0.0.1:0`, from its log line ("" if
/// the master exited or never logged it).
inline std::string waitForControlPort(const std::filesystem::path& log, pid_t master) {
    const auto control =
        waitForLine(log, std::regex(R"(control commands on 127\.0\.0\.1:(\d+))"), master);
    return control.empty() ? std::string() : control[1].str();
}

/// Runs `igi-ctl --connect 127.0.0.1:PORT ARGS...`, its output going to `log`.
inline ProcessResult runCtl(const std::filesystem::path& log, const std::string& port,
                            const std::vector<std::string>& args) {
    std::vector<std::string> command = {(binDir() / "igi-ctl").string(), "--connect",
                                        "127.0.0.1:" + port};
    command.insert(command.end(), args.begin(), args.end());
    return runProcess(command, log, 60);
}

/// A session that renders until told to stop, so that a fault always lands mid-session however
/// fast or slow the machine is; its image is then compared with an undisturbed run of as many
/// frames as it finished.
struct OpenSession {
    std::filesystem::path dir;
    std::filesystem::path log;
    pid_t master = -1;
    std::string port, controlPort;

    OpenSession(const std::filesystem::path& d, std::vector<std::string> extra)
        : dir(d), log(d / "master.log") {
        auto args = sceneArgs(0);
        args.insert(args.end(), {"--output", (dir / "faulty.exr").string(), "--stats-json",
                                 (dir / "stats.json").string(), "--control", "127.0.0.1:0"});
        args.insert(args.end(), extra.begin(), extra.end());
        master = spawnProcess(masterCommand(args), log);
        const auto listening =
            waitForLine(log, std::regex(R"(listening on 127\.0\.0\.1:(\d+))"), master);
        if (!listening.empty()) port = listening[1].str();
        controlPort = waitForControlPort(log, master);
    }
    ~OpenSession() {
        if (master > 0 && kill(master, 0) == 0) kill(master, SIGKILL), waitProcess(master, 10);
    }

    bool started() const { return master > 0 && !port.empty() && !controlPort.empty(); }

    /// The highest frame number the master has reported finished so far (-1: none).
    int lastFrame() const { return lastFrameIn(log); }

    /// Waits until `count` more frames than now have finished.
    bool waitFrames(int count) {
        const int target = lastFrame() + count;
        return !waitForLine(log, std::regex("frame +" + std::to_string(target) + ":"), master, 120)
                    .empty();
    }

    /// Starts a client process that joins the session (with the shared secret in `secret`),
    /// its output going to dir/joiner.log, and waits until the master says client `id` is
    /// ready. Its pid, or -1 if it did not start or never became ready.
    pid_t join(const std::filesystem::path& secret, int id) const {
        const pid_t joiner =
            spawnProcess(clientCommand({"--connect", "127.0.0.1:" + port, "--threads", "1",
                                        "--secret-file", secret.string()}),
                         dir / "joiner.log");
        if (joiner <= 0) return -1;
        const std::regex ready("client " + std::to_string(id) + R"( \(.*\) is ready)");
        return waitForLine(log, ready, master).empty() ? -1 : joiner;
    }

    /// Stops the session; returns how many frames it finished (-1 on failure).
    int stop() {
        const ProcessResult r = runCtl(dir / "ctl.log", controlPort, {"stop"});
        if (r.exitCode != 0 || waitProcess(master, 300) != 0) return -1;
        master = -1;
        std::ifstream file(dir / "stats.json");
        return int(nlohmann::json::parse(file)["frames"].size());
    }
};

}  // namespace igi::testing
