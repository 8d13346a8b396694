#include "LocalClients.h"

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
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

namespace {

/// A pipe for a client's stderr, or throws. Both ends close on exec: its client gets the
/// write end only as its descriptor 2, through the spawn's dup2, so that no other process the
/// master starts holds it open and keeps the reader from seeing the end.
std::array<int, 2> stderrPipe() {
    std::array<int, 2> fds{-1, -1};
    if (pipe2(fds.data(), O_CLOEXEC) != 0)
        throw std::runtime_error(std::string("cannot make a pipe for the local clients' stderr: ") +
                                 std::strerror(errno));
    return fds;
}

}  // namespace

void LocalClients::readLines(std::vector<int> fds, LineHandler onLine) {
    // One pipe per client: a client's line cut into several writes stays whole.
    std::vector<std::string> pending(fds.size());
    std::vector<pollfd> polled;
    for (int fd : fds) polled.push_back({fd, POLLIN, 0});
    std::size_t open = fds.size();
    char chunk[4096];
    while (open > 0) {
        if (poll(polled.data(), polled.size(), -1) < 0) {
            if (errno == EINTR) continue;
            break;
        }
        for (std::size_t i = 0; i < polled.size(); ++i) {
            if (polled[i].fd < 0 || polled[i].revents == 0) continue;
            const ssize_t n = read(polled[i].fd, chunk, sizeof chunk);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) {  // this client has exited: its last line, even without a newline
                if (!pending[i].empty()) onLine(pending[i]);
                close(polled[i].fd);
                polled[i].fd = -1;
                --open;
                continue;
            }
            std::string& text = pending[i];
            text.append(chunk, std::size_t(n));
            std::size_t start = 0;
            for (std::size_t nl; (nl = text.find('\n', start)) != std::string::npos; start = nl + 1)
                onLine(text.substr(start, nl - start));
            text.erase(0, start);
        }
    }
    for (const pollfd& p : polled)
        if (p.fd >= 0) close(p.fd);
}

std::string LocalClients::clientExecutableBesideSelf() {
    const auto self = std::filesystem::read_symlink("/proc/self/exe");
    return (self.parent_path() / "igi-client").string();
}

void LocalClients::start(const std::string& executable, const std::vector<std::string>& arguments,
                         int count, const std::vector<std::string>& environment,
                         LineHandler onStderrLine) {
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
    std::vector<int> readEnds;
    // A client's write end is its alone once it is started: the reader sees the end of a pipe
    // when its client exits.
    auto startReader = [&] {
        if (!readEnds.empty())
            stderrReader_ =
                std::thread(&LocalClients::readLines, this, readEnds, std::move(onStderrLine));
    };
    for (int i = 0; i < count; ++i) {
        std::vector<std::string> args{executable};
        args.insert(args.end(), arguments.begin(), arguments.end());
        std::vector<char*> argv;
        for (auto& a : args) argv.push_back(a.data());
        argv.push_back(nullptr);
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        std::array<int, 2> pipeFds{-1, -1};
        if (onStderrLine) {
            pipeFds = stderrPipe();
            posix_spawn_file_actions_adddup2(&actions, pipeFds[1], STDERR_FILENO);
        }
        pid_t pid = 0;
        const int rc =
            posix_spawn(&pid, executable.c_str(), &actions, nullptr, argv.data(), envp.data());
        posix_spawn_file_actions_destroy(&actions);
        if (pipeFds[1] >= 0) close(pipeFds[1]);
        if (rc != 0) {
            if (pipeFds[0] >= 0) close(pipeFds[0]);
            startReader();
            throw std::runtime_error("cannot start " + executable + ": " + std::strerror(rc));
        }
        if (pipeFds[0] >= 0) readEnds.push_back(pipeFds[0]);
        spdlog::info("started local client {} (pid {})", i + 1, pid);
        pids_.push_back(pid);
    }
    startReader();
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
    // Every client has exited: the pipe has ended, and the reader with it.
    if (stderrReader_.joinable()) stderrReader_.join();
    return killed;
}

}  // namespace igi
