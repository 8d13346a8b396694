// Sessions across real network links: master and clients on "hosts" that are network
// namespaces of this machine (tests/NetworkLab.h), each with its own address and link.
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <sstream>

#include <gtest/gtest.h>

#include "NetworkLab.h"
#include "Session.h"

namespace igi::testing {
namespace {

/// Ends the processes it holds when the test ends, however it ends (before the lab is removed).
struct Processes {
    std::vector<pid_t> pids;
    ~Processes() {
        for (pid_t p : pids)
            if (p > 0 && kill(p, 0) == 0) kill(p, SIGKILL), waitProcess(p, 10);
    }
};

int countMatches(const std::string& text, const std::regex& pattern) {
    return int(std::distance(std::sregex_iterator(text.begin(), text.end(), pattern),
                             std::sregex_iterator()));
}

// Waits until the log has `count` matches of `pattern`; false on timeout or the process's end.
bool waitForCount(const std::filesystem::path& log, const std::regex& pattern, int count, pid_t pid,
                  double seconds) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < deadline) {
        if (countMatches(readFile(log), pattern) >= count) return true;
        if (!processRunning(pid)) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
}

std::string namespaces() {
    const auto dir = scratchDir("netns-list");
    const ProcessResult r = runProcess({"/sbin/ip", "netns", "list"}, dir / "list.log");
    std::filesystem::remove_all(dir);
    return r.output;
}

// Whatever a lab made is gone when it is, even when the test's folder went first.
TEST(Lan, TheLabRemovesEveryNamespaceItMade) {
    std::string host;
    {
        const auto dir = scratchDir("lan-cleanup");
        NetworkLab lab(2, dir);
        if (!lab.ok()) GTEST_SKIP() << "no test hosts: " << lab.error();
        host = lab.host(1);
        ASSERT_NE(namespaces().find(host), std::string::npos);
        std::filesystem::remove_all(dir);
    }
    const std::string prefix = host.substr(0, host.find('-') + 1);
    EXPECT_EQ(namespaces().find(prefix), std::string::npos) << namespaces();
}

// Whether `ip netns list` output names `name` (each line: the name, then maybe "(id: N)").
bool listed(const std::string& list, const std::string& name) {
    std::istringstream lines(list);
    for (std::string line; std::getline(lines, line);)
        if (line.substr(0, line.find(' ')) == name) return true;
    return false;
}

// A test killed by a signal leaves its namespaces (no destructor runs): the next lab removes
// those of processes that are gone, and keeps those of live ones.
TEST(Lan, ALabRemovesTheNamespacesOfKilledTests) {
    if (geteuid() != 0) GTEST_SKIP() << "no test hosts: needs root";
    // A pid that was a process and is no more: a child that has exited and been reaped.
    const pid_t gone = fork();
    if (gone == 0) _exit(0);
    ASSERT_GT(gone, 0);
    waitpid(gone, nullptr, 0);
    const std::string stale = "igi" + std::to_string(gone) + "-h0";
    const std::string live = "igi" + std::to_string(getppid()) + "-h0";  // ctest, alive
    const auto dir = scratchDir("lan-leftovers");
    for (const auto& name : {stale, live})
        ASSERT_EQ(runProcess({"/sbin/ip", "netns", "add", name}, dir / "add.log", 30).exitCode, 0)
            << name;
    std::string skip;
    {
        NetworkLab lab(1, dir);
        if (!lab.ok()) skip = lab.error();
    }
    const std::string after = namespaces();
    for (const auto& name : {stale, live})
        runProcess({"/sbin/ip", "netns", "del", name}, dir / "del.log", 30);
    std::filesystem::remove_all(dir);
    if (!skip.empty()) GTEST_SKIP() << "no test hosts: " << skip;
    EXPECT_FALSE(listed(after, stale)) << after;
    EXPECT_TRUE(listed(after, live)) << after;
}

// The issue's LAN test: a client whose link goes down mid-session is dropped, its tiles are
// rendered by the other, and the image equals an undisturbed run's; when the link comes back the
// client joins again by itself.
TEST(Lan, AClientWhoseLinkIsCutIsReplacedAndComesBackWhenTheLinkDoes) {
    const auto dir = scratchDir("lan-cut");
    NetworkLab lab(3, dir);
    if (!lab.ok()) GTEST_SKIP() << "no test hosts: " << lab.error();
    Processes processes;

    const auto secret = dir / "cluster.secret";
    std::ofstream(secret) << "lan-test-secret-0123456789abcdef\n";
    chmod(secret.c_str(), 0600);
    const std::string masterAddress = NetworkLab::address(0) + ":7878";
    auto args = sceneArgs(0, masterAddress);
    args.insert(args.end(), {"--clients", "2", "--secret-file", secret.string(), "--read-timeout",
                             "2", "--output", (dir / "faulty.exr").string(), "--stats-json",
                             (dir / "stats.json").string(), "--control", "127.0.0.1:7879"});
    const auto log = dir / "master.log";
    const pid_t master = spawnProcess(lab.in(0, masterCommand(args)), log);
    processes.pids.push_back(master);
    for (int i = 1; i <= 2; ++i)
        processes.pids.push_back(spawnProcess(
            lab.in(i, clientCommand({"--connect", masterAddress, "--threads", "1", "--secret-file",
                                     secret.string(), "--read-timeout", "2", "--reconnect-seconds",
                                     "120"})),
            dir / ("client" + std::to_string(i) + ".log")));

    const std::regex ready(R"(client \d+ \(.*\) is ready)");
    ASSERT_TRUE(waitForCount(log, ready, 2, master, 120)) << readFile(log);
    ASSERT_FALSE(waitForLine(log, std::regex(R"(frame +3:)"), master, 120).empty())
        << readFile(log);

    // The link of host 1 goes down: nothing reaches it and nothing leaves it.
    ASSERT_TRUE(lab.setLink(1, false)) << lab.error();
    const std::regex left(R"(client \d+ left)");
    ASSERT_TRUE(waitForCount(log, left, 1, master, 60)) << readFile(log);
    const int afterCut = lastFrameIn(log);
    ASSERT_FALSE(
        waitForLine(log, std::regex("frame +" + std::to_string(afterCut + 3) + ":"), master, 120)
            .empty())
        << "the session did not go on with one client\n"
        << readFile(log);

    // Back up: the client finds its master again by itself.
    ASSERT_TRUE(lab.setLink(1, true)) << lab.error();
    const std::regex fromHost1(
        "client \\d+ connected from " +
        std::regex_replace(NetworkLab::address(1), std::regex("\\."), "\\.") + ":");
    ASSERT_TRUE(waitForCount(log, fromHost1, 2, master, 150)) << readFile(log);
    ASSERT_TRUE(waitForCount(log, ready, 3, master, 60)) << readFile(log);
    const int afterReturn = lastFrameIn(log);
    ASSERT_FALSE(
        waitForLine(log, std::regex("frame +" + std::to_string(afterReturn + 3) + ":"), master, 120)
            .empty())
        << readFile(log);

    const ProcessResult stop = runProcess(
        lab.in(0, {(binDir() / "igi-ctl").string(), "--connect", "127.0.0.1:7879", "stop"}),
        dir / "ctl.log");
    ASSERT_EQ(stop.exitCode, 0) << stop.output;
    ASSERT_EQ(waitProcess(master, 120), 0) << readFile(log);
    std::ifstream stats(dir / "stats.json");
    const int frames = int(nlohmann::json::parse(stats)["frames"].size());
    ASSERT_GT(frames, afterReturn);
    expectSameAsUndisturbed(dir, frames);
    if (!HasFailure()) std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace igi::testing
