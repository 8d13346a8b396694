// A long session's memory: the master must not keep something for every frame it renders (a
// session runs for days). Thousands of small frames with the example animation, the control
// port and --stats-json, the master's resident memory sampled as they go; the growth per frame
// over the second half (after the warm-up) must stay far below what keeping a record per frame
// costs. Memory, not time: the bound holds on a slow machine as on a fast one.
#include <sys/types.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "Session.h"

namespace igi {
namespace {

using namespace igi::testing;
namespace fs = std::filesystem;

/// The resident memory of a process in kB (-1 once it is gone).
long residentKb(pid_t pid) {
    std::ifstream status("/proc/" + std::to_string(pid) + "/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
    return -1;
}

/// The last frame a master's log reports finished, from its tail only: the log grows by a line
/// a frame, and reading it whole every few milliseconds would cost the test more than the
/// session.
int lastFrameInTail(const fs::path& log) {
    std::ifstream in(log, std::ios::binary | std::ios::ate);
    const std::streamoff size = in.tellg();
    if (size <= 0) return -1;
    const std::streamoff from = std::max<std::streamoff>(0, size - 4096);
    in.seekg(from);
    std::string tail(std::size_t(size - from), '\0');
    in.read(tail.data(), std::streamsize(tail.size()));
    static const std::regex frameLine(R"(frame +(\d+):)");
    int last = -1;
    for (std::sregex_iterator it(tail.begin(), tail.end(), frameLine), end; it != end; ++it)
        last = std::max(last, std::stoi((*it)[1].str()));
    return last;
}

/// Least-squares slope of y over x.
double slope(const std::vector<std::pair<double, double>>& points) {
    double mx = 0, my = 0;
    for (const auto& [x, y] : points) mx += x, my += y;
    mx /= double(points.size());
    my /= double(points.size());
    double sxy = 0, sxx = 0;
    for (const auto& [x, y] : points) sxy += (x - mx) * (y - my), sxx += (x - mx) * (x - mx);
    return sxx > 0 ? sxy / sxx : 0.0;
}

TEST(LongSession, TheMastersMemoryStaysFlatFrameAfterFrame) {
    // Keeping a record per frame (the statistics of every frame and of every client's frames,
    // as the master did) cost about 900 bytes a frame with two clients: 1.8 MB over the 2,000
    // frames measured here. The bound leaves room for the allocator's noise, and no room for a
    // record per frame.
    constexpr int kFrames = 4000;
    constexpr double kMaxBytesPerFrame = 200;
    const fs::path dir = scratchDir("long-session");
    const fs::path log = dir / "master.log";
    const pid_t master = spawnProcess(
        masterCommand(
            {"--scene",           (sourceDir() / "scenes/cornell/cornell.json").string(),
             "--animation",       (sourceDir() / "scenes/cornell/example.anim.json").string(),
             "--width",           "64",
             "--height",          "48",
             "--frames",          std::to_string(kFrames),
             "--local-clients",   "2",
             "--client-threads",  "1",
             "--direct-samples",  "1",
             "--indirect-vpls",   "2",
             "--caustic-photons", "10",
             "--control",         "127.0.0.1:0",
             "--stats-json",      (dir / "stats.json").string(),
             "--listen",          "127.0.0.1:0",
             "--log-level",       "info"}),
        log);
    ASSERT_GT(master, 0);
    std::vector<std::pair<double, double>> secondHalf;  // (frame, resident kB)
    // Not a time limit on the frames: a guard against a master that hangs.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(15);
    for (;;) {
        const int frame = lastFrameInTail(log);
        const long kb = residentKb(master);
        if (kb < 0 || !processRunning(master)) break;
        if (std::chrono::steady_clock::now() > deadline) {
            kill(master, SIGKILL);
            waitProcess(master, 10);
            FAIL() << "the master did not finish " << kFrames << " frames in 15 minutes";
        }
        // Up to the last frame: the outputs written after it are not a frame's cost.
        if (frame >= kFrames / 2 && frame < kFrames - 1) secondHalf.emplace_back(frame, double(kb));
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    ASSERT_EQ(waitProcess(master, 600), 0) << readFile(log);
    ASSERT_GE(secondHalf.size(), 20u) << "too few samples of the second half";
    const double bytesPerFrame = slope(secondHalf) * 1024;
    EXPECT_LT(bytesPerFrame, kMaxBytesPerFrame)
        << "the master's memory grows with the frames: " << secondHalf.front().second << " kB at "
        << "frame " << secondHalf.front().first << ", " << secondHalf.back().second
        << " kB at frame " << secondHalf.back().first;
    std::cout << "master memory over frames " << secondHalf.front().first << " to "
              << secondHalf.back().first << ": " << bytesPerFrame << " bytes per frame ("
              << secondHalf.size() << " samples, " << secondHalf.front().second << " to "
              << secondHalf.back().second << " kB)\n";

    // The statistics written as the frames closed are all there, in order, as one JSON file.
    std::ifstream file(dir / "stats.json");
    const nlohmann::json stats = nlohmann::json::parse(file);
    ASSERT_EQ(stats["frames"].size(), std::size_t(kFrames));
    for (int f = 0; f < kFrames; ++f) ASSERT_EQ(stats["frames"][f]["index"], f);
    EXPECT_EQ(stats["clients"].size(), 2u);
    EXPECT_FALSE(fs::exists(dir / "stats.json.frames.jsonl")) << "the frames' sidecar is left";
    fs::remove_all(dir);
}

}  // namespace
}  // namespace igi
