#pragma once
// Runs the project's executables from tests: real processes, output captured.

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "util/TestPaths.h"

extern char** environ;

namespace igi::testing {

struct ProcessResult {
    int exitCode = -1;   ///< -1 if killed on timeout
    std::string output;  ///< stdout and stderr together
};

/// A fresh empty folder for one test's files.
inline std::filesystem::path scratchDir(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() /
                     ("igi-e2e-" + name + "-" + std::to_string(getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

/// Starts a process with its output going to `log`; returns its pid.
inline pid_t spawnProcess(const std::vector<std::string>& args, const std::filesystem::path& log) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    std::vector<std::string> copy = args;
    std::vector<char*> argv;
    for (auto& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = -1;
    if (posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ) != 0) pid = -1;
    posix_spawn_file_actions_destroy(&actions);
    return pid;
}

/// Whether a process is still running. A child that has ended but is not yet waited for (a
/// zombie) still answers kill(pid, 0); waitid with WNOWAIT sees that it ended and leaves it for
/// waitProcess to collect its exit code.
inline bool processRunning(pid_t pid) {
    siginfo_t info{};
    if (waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0)
        return info.si_pid != pid;  // si_pid stays 0 while the child runs
    return kill(pid, 0) == 0;       // not our child: all we can ask is whether the pid exists
}

/// Waits for a process; kills it after `timeoutSeconds`. Returns its exit code, -1 if killed.
inline int waitProcess(pid_t pid, double timeoutSeconds) {
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(timeoutSeconds);
    int status = 0;
    while (waitpid(pid, &status, WNOHANG) == 0) {
        if (std::chrono::steady_clock::now() > deadline) {
            kill(pid, SIGKILL);
            waitpid(pid, &status, 0);
            return -1;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

inline std::string readFile(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

/// Runs a command to completion and returns its exit code and output.
inline ProcessResult runProcess(const std::vector<std::string>& args,
                                const std::filesystem::path& log, double timeoutSeconds = 300) {
    ProcessResult r;
    const pid_t pid = spawnProcess(args, log);
    if (pid < 0) return r;
    r.exitCode = waitProcess(pid, timeoutSeconds);
    r.output = readFile(log);
    return r;
}

}  // namespace igi::testing
