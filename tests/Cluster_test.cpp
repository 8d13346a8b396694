// scripts/cluster.sh end to end: the launcher runs on one test host (a network namespace,
// tests/NetworkLab.h) and reaches the others through real sshd servers (tests/SshServers.h),
// as it would reach the machines of a LAN.
#include <dirent.h>
#include <sys/stat.h>

#include <atomic>
#include <set>

#include <gtest/gtest.h>

#include "NetworkLab.h"
#include "Session.h"
#include "SshServers.h"

namespace igi::testing {
namespace {

namespace fs = std::filesystem;

struct ProcessInfo {
    pid_t pid;
    std::string program;  ///< argv[0]'s file name
    std::string line;     ///< the command line, words separated by spaces
};

/// Every process (but this one) whose command line mentions `text`.
std::vector<ProcessInfo> processesMentioning(const std::string& text) {
    std::vector<ProcessInfo> found;
    DIR* proc = opendir("/proc");
    if (!proc) return found;
    while (const dirent* e = readdir(proc)) {
        if (!std::isdigit(static_cast<unsigned char>(e->d_name[0]))) continue;
        std::string line = readFile(fs::path("/proc") / e->d_name / "cmdline");
        if (line.find(text) == std::string::npos || atoi(e->d_name) == getpid()) continue;
        const std::string program = fs::path(line.substr(0, line.find('\0'))).filename();
        std::replace(line.begin(), line.end(), '\0', ' ');
        found.push_back({atoi(e->d_name), program, line});
    }
    closedir(proc);
    return found;
}

/// igi-master and igi-client processes started for the test folder `dir` (their command lines
/// name files in it), not the ssh processes whose remote command names igi-client.
std::vector<ProcessInfo> renderProcessesOf(const fs::path& dir) {
    std::vector<ProcessInfo> found;
    for (const ProcessInfo& p : processesMentioning(dir.string()))
        if (p.program == "igi-client" || p.program == "igi-master") found.push_back(p);
    return found;
}

/// Ends what a failed test left running (a passing test leaves nothing): every process that
/// names the test's folder (launcher, its ssh clients, master, clients), but not the sshd
/// servers, which SshServers ends.
struct KillLeftovers {
    fs::path dir;
    ~KillLeftovers() {
        for (const ProcessInfo& p : processesMentioning(dir.string()))
            if (p.program != "sshd") kill(p.pid, SIGKILL);
    }
};

/// The lab the launcher tests share: host 0 runs the launcher and the master, hosts 1 and 2
/// run sshd and receive the clients.
struct ClusterLab {
    fs::path dir;
    NetworkLab lab;
    std::unique_ptr<SshServers> ssh;
    std::string skip;

    explicit ClusterLab(const std::string& name) : dir(scratchDir(name)), lab(3, dir) {
        if (!lab.ok()) {
            skip = "no test hosts: " + lab.error();
            return;
        }
        ssh = std::make_unique<SshServers>(lab, std::vector<int>{1, 2}, dir);
        if (!ssh->available()) skip = "no ssh servers: " + ssh->error();
    }

    /// The hosts file: host 1 by the plain form, host 2 with the user and port columns.
    fs::path hostsFile() const {
        const fs::path f = dir / "hosts";
        std::ofstream(f) << "# test hosts\n"
                         << NetworkLab::address(1) << " 1\n"
                         << NetworkLab::address(2) << " 1 root 22  # user and port given\n";
        return f;
    }

    /// scripts/cluster.sh, run on host 0, with the test's ssh configuration and folders.
    std::vector<std::string> launcher(const fs::path& hosts, std::vector<std::string> extra,
                                      const std::vector<std::string>& masterArgs) const {
        std::vector<std::string> c = {(sourceDir() / "scripts/cluster.sh").string(),
                                      "--hosts",
                                      hosts.string(),
                                      "--ssh-config",
                                      ssh->config().string(),
                                      "--remote-dir",
                                      (dir / "remote").string(),
                                      "--logs",
                                      (dir / "logs").string(),
                                      "--status-seconds",
                                      "1"};
        c.insert(c.end(), extra.begin(), extra.end());
        c.push_back("--");
        c.insert(c.end(), masterArgs.begin(), masterArgs.end());
        return lab.in(0, c);
    }
};

/// The master's arguments: the Cornell scene, small, `frames` frames (0: until stopped).
std::vector<std::string> masterArgs(int frames, const fs::path& output) {
    std::vector<std::string> a = {
        "--scene",  (sourceDir() / "scenes/cornell/cornell.json").string(),
        "--width",  "160",
        "--height", "120",
        "--frames", std::to_string(frames)};
    if (!output.empty()) a.insert(a.end(), {"--output", output.string()});
    return a;
}

bool remoteFolderEmpty(const fs::path& remote) {
    return !fs::exists(remote) || fs::is_empty(remote);
}

// The issue's launcher test: a whole session over ssh to two hosts. The secret reaches them
// with mode 600 and never on a command line; every log lands in one folder; the image equals a
// local run's; nothing the launcher started is left afterwards.
TEST(Cluster, ASessionOverSshEqualsALocalRunAndLeavesNothingBehind) {
    ClusterLab c("cluster-session");
    KillLeftovers leftovers{c.dir};
    if (!c.skip.empty()) GTEST_SKIP() << c.skip;
    ASSERT_TRUE(c.ssh->ok()) << "the ssh servers did not start: " << c.ssh->error();
    const std::string secretText = "cluster-test-secret-5d1c0e7a9b";
    const fs::path secret = c.dir / "cluster.secret";
    std::ofstream(secret) << secretText << "\n";
    chmod(secret.c_str(), 0600);

    // While the session runs: no process shows the secret, and every copy of it is mode 600.
    std::atomic<bool> running{true};
    std::set<std::string> shown, badModes, copies;
    std::thread watcher([&] {
        while (running) {
            for (const ProcessInfo& p : processesMentioning(secretText)) shown.insert(p.line);
            std::error_code e;
            for (fs::recursive_directory_iterator it(c.dir / "remote", e), end; !e && it != end;
                 it.increment(e))
                if (it->path().filename() == "secret") {
                    copies.insert(it->path().string());
                    struct stat st {};
                    if (stat(it->path().c_str(), &st) == 0 && (st.st_mode & 0777) != 0600)
                        badModes.insert(it->path().string());
                }
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
    });
    const ProcessResult r = runProcess(c.launcher(c.hostsFile(), {"--secret-file", secret.string()},
                                                  masterArgs(6, c.dir / "cluster.exr")),
                                       c.dir / "launcher.log", 600);
    running = false;
    watcher.join();

    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(shown.empty()) << "the secret was on a command line: " << *shown.begin();
    EXPECT_EQ(copies.size(), 2u) << "one copy per host, seen while the session ran";
    EXPECT_TRUE(badModes.empty()) << *badModes.begin() << " is not mode 600";
    EXPECT_TRUE(remoteFolderEmpty(c.dir / "remote")) << "the secret's copies outlived the session";
    EXPECT_TRUE(renderProcessesOf(c.dir).empty()) << renderProcessesOf(c.dir).front().line;

    // One folder with every log: the launcher's, the master's, and each client's (which ran on
    // its own host: it connected from that host's address).
    const fs::path logs = c.dir / "logs";
    const std::string master = readFile(logs / "master.log");
    for (int h = 1; h <= 2; ++h) {
        EXPECT_NE(master.find("connected from " + NetworkLab::address(h) + ":"), std::string::npos)
            << master;
        const std::string client = readFile(logs / ("client-" + std::to_string(h - 1) + ".log"));
        EXPECT_NE(client.find("igi-cluster: client pid "), std::string::npos) << client;
        EXPECT_NE(client.find("scene"), std::string::npos) << client;
    }
    // Status lines (those naming each host with its rates are checked in the next test, whose
    // session lasts until stopped: six small frames can end before both clients show rates).
    const std::string status = readFile(logs / "cluster.log");
    EXPECT_TRUE(std::regex_search(status, std::regex(R"(frames \d+/6, )"))) << status;

    auto local = masterArgs(6, c.dir / "local.exr");
    local.insert(local.end(), {"--local-clients", "1"});
    const ProcessResult l = runProcess(masterCommand(local), c.dir / "local.log");
    ASSERT_EQ(l.exitCode, 0) << l.output;
    expectSameImage(c.dir / "cluster.exr", c.dir / "local.exr");
    if (!HasFailure()) fs::remove_all(c.dir);
}

/// Starts the launcher on a session that runs until stopped; returns its pid once the status
/// names both hosts with their clients' rates (-1 if it never does).
pid_t startOpenSession(const ClusterLab& c, const fs::path& log) {
    const pid_t launcher = spawnProcess(c.launcher(c.hostsFile(), {}, masterArgs(0, {})), log);
    for (int h = 1; h <= 2 && launcher > 0; ++h)
        if (waitForLine(log, std::regex(NetworkLab::address(h) + ": 1 threads"), launcher, 180)
                .empty())
            return -1;
    return launcher;
}

/// Nothing the launcher started is left: no master, no client, no copy of the secret.
void expectNothingLeft(const ClusterLab& c) {
    std::vector<ProcessInfo> left = renderProcessesOf(c.dir);
    for (int i = 0; i < 50 && !left.empty(); ++i) {  // a client may take a moment to exit
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
        left = renderProcessesOf(c.dir);
    }
    EXPECT_TRUE(left.empty()) << left.front().line;
    EXPECT_TRUE(remoteFolderEmpty(c.dir / "remote"));
}

// Ctrl-C while the session runs: the launcher stops the master and every client it started on
// the hosts, and removes the secret's copies.
TEST(Cluster, CtrlCStopsEverythingTheLauncherStarted) {
    ClusterLab c("cluster-interrupt");
    KillLeftovers leftovers{c.dir};
    if (!c.skip.empty()) GTEST_SKIP() << c.skip;
    ASSERT_TRUE(c.ssh->ok()) << "the ssh servers did not start: " << c.ssh->error();
    const fs::path log = c.dir / "launcher.log";
    const pid_t launcher = startOpenSession(c, log);
    ASSERT_GT(launcher, 0) << readFile(log);
    ASSERT_EQ(renderProcessesOf(c.dir).size(), 3u) << "a master and two clients";

    kill(launcher, SIGINT);
    EXPECT_EQ(waitProcess(launcher, 60), 130) << readFile(log);
    EXPECT_NE(readFile(log).find("interrupted"), std::string::npos) << readFile(log);
    expectNothingLeft(c);
    if (!HasFailure()) fs::remove_all(c.dir);
}

// The master dies mid-session (killed): the launcher stops the clients, which would otherwise
// keep trying to reach it, and exits with the master's status.
TEST(Cluster, AMasterThatDiesTakesItsClientsWithIt) {
    ClusterLab c("cluster-master-dies");
    KillLeftovers leftovers{c.dir};
    if (!c.skip.empty()) GTEST_SKIP() << c.skip;
    ASSERT_TRUE(c.ssh->ok()) << "the ssh servers did not start: " << c.ssh->error();
    const fs::path log = c.dir / "launcher.log";
    const pid_t launcher = startOpenSession(c, log);
    ASSERT_GT(launcher, 0) << readFile(log);
    int killed = 0;
    for (const ProcessInfo& p : renderProcessesOf(c.dir))
        if (p.program == "igi-master") killed += kill(p.pid, SIGKILL) == 0;
    ASSERT_EQ(killed, 1);

    EXPECT_EQ(waitProcess(launcher, 60), 128 + SIGKILL) << readFile(log);
    EXPECT_NE(readFile(log).find("the master ended with exit code 137"), std::string::npos)
        << readFile(log);
    expectNothingLeft(c);
    if (!HasFailure()) fs::remove_all(c.dir);
}

// Hosts that fail the check stop the launcher before it starts anything, each named with why.
TEST(Cluster, UnreachableHostsAndOtherBuildsAreRefusedBeforeAnythingStarts) {
    ClusterLab c("cluster-check");
    KillLeftovers leftovers{c.dir};
    if (!c.skip.empty()) GTEST_SKIP() << c.skip;
    ASSERT_TRUE(c.ssh->ok()) << "the ssh servers did not start: " << c.ssh->error();

    // 10.213.0.9 is in the lab's network, but no host has it.
    const fs::path hosts = c.dir / "hosts-unreachable";
    std::ofstream(hosts) << NetworkLab::address(1) << " 1\n10.213.0.9 1\n";
    ProcessResult r = runProcess(c.launcher(hosts, {}, masterArgs(2, {})), c.dir / "a.log", 120);
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("10.213.0.9: not reachable over ssh"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find(NetworkLab::address(1) + ": "), std::string::npos)
        << "the good host was named as failing:\n"
        << r.output;
    EXPECT_FALSE(fs::exists(c.dir / "logs" / "master.log")) << "a master was started";

    // A host whose igi-client is another build.
    const fs::path otherBin = c.dir / "other-bin";
    fs::create_directories(otherBin);
    std::ofstream(otherBin / "igi-client") << "#!/bin/sh\necho 0.0-someone-elses-build\n";
    fs::permissions(otherBin / "igi-client", fs::perms::owner_all);
    r = runProcess(c.launcher(c.hostsFile(), {"--bin", otherBin.string()}, masterArgs(2, {})),
                   c.dir / "b.log", 120);
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("its igi-client is build '0.0-someone-elses-build'"), std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(c.dir / "logs" / "master.log")) << "a master was started";

    // A malformed hosts file names its line and field.
    const fs::path bad = c.dir / "hosts-bad";
    std::ofstream(bad) << NetworkLab::address(1) << " 1\n" << NetworkLab::address(2) << " many\n";
    r = runProcess(c.launcher(bad, {}, masterArgs(2, {})), c.dir / "c.log", 60);
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find(bad.string() + " line 2: THREADS 'many' is not a whole number"),
              std::string::npos)
        << r.output;
    EXPECT_TRUE(renderProcessesOf(c.dir).empty());
    if (!HasFailure()) fs::remove_all(c.dir);
}

}  // namespace
}  // namespace igi::testing
