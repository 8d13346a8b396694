#include "LocalClients.h"

#include <spawn.h>
#include <sys/wait.h>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <thread>

#include <spdlog/spdlog.h>

extern char** environ;

namespace igi {

LocalClients::~LocalClients() {
    stop(0);
}

std::string LocalClients::clientExecutableBesideSelf() {
    const auto self = std::filesystem::read_symlink("/proc/self/exe");
    return (self.parent_path() / "igi-client").string();
}

void LocalClients::start(const std::string& executable, const std::vector<std::string>& arguments,
                         int count, const std::vector<std::string>& environment) {
    std::vector<std::string> env;
    for (char** e = environ; *e; ++e) {
        const std::string entry = *e;
        const std::string name = entry.substr(0, entry.find('='));
        bool replaced = false;
        for (const auto& extra : environment) replaced |= extra.substr(0, extra.find('=')) == name;
        if (!replaced) env.push_back(entry);
    }
    env.insert(env.end(), environment.begin(), environment.end());
    std::vector<char*> envp;
    for (auto& e : env) envp.push_back(e.data());
    envp.push_back(nullptr);
    for (int i = 0; i < count; ++i) {
        std::vector<std::string> args{executable};
        args.insert(args.end(), arguments.begin(), arguments.end());
        std::vector<char*> argv;
        for (auto& a : args) argv.push_back(a.data());
        argv.push_back(nullptr);
        pid_t pid = 0;
        const int rc =
            posix_spawn(&pid, executable.c_str(), nullptr, nullptr, argv.data(), envp.data());
        if (rc != 0)
            throw std::runtime_error("cannot start " + executable + ": " + std::strerror(rc));
        spdlog::info("started local client {} (pid {})", i + 1, pid);
        pids_.push_back(pid);
    }
}

int LocalClients::stop(double seconds) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    int killed = 0;
    for (pid_t pid : pids_) {
        for (;;) {
            int status = 0;
            const pid_t r = waitpid(pid, &status, WNOHANG);
            if (r == pid || (r < 0 && errno == ECHILD)) break;
            if (std::chrono::steady_clock::now() >= deadline) {
                spdlog::warn("local client pid {} did not exit; killing it", pid);
                kill(pid, SIGKILL);
                waitpid(pid, &status, 0);
                ++killed;
                break;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
    }
    pids_.clear();
    return killed;
}

}  // namespace igi
