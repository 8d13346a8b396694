#pragma once
// Real OpenSSH servers on test hosts (tests/NetworkLab.h): one sshd per host, in that host's
// namespace, on its address, with host and user keys generated into the test's folder by
// ssh-keygen. The client side gets an ssh_config (identity, known hosts pinned to the generated
// host keys, strict checking) to hand to `ssh -F`. Nothing outside the test's folder is used
// except sshd's privilege separation folder /run/sshd, which sshd insists on: made if missing
// and then removed again. The destructor ends every sshd. Needs root and Debian's
// openssh-server and openssh-client (the test command installs them).

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "NetworkLab.h"
#include "Session.h"

namespace igi::testing {

class SshServers {
  public:
    SshServers(const NetworkLab& lab, const std::vector<int>& hosts,
               const std::filesystem::path& dir)
        : dir_(dir) {
        // One test with sshd servers at a time: each may make and remove /run/sshd, which
        // another's running sshd needs. The lock is on the test executable itself, so that
        // nothing is left behind; it goes with the descriptor.
        lock_ = open("/proc/self/exe", O_RDONLY | O_CLOEXEC);
        if (lock_ >= 0) flock(lock_, LOCK_EX);
        ok_ = start(lab, hosts);
    }

    ~SshServers() {
        for (pid_t p : pids_)
            if (kill(p, SIGTERM) == 0 && waitProcess(p, 10) < 0) kill(p, SIGKILL);
        if (madeRunDir_) std::filesystem::remove("/run/sshd");
        if (lock_ >= 0) close(lock_);
    }

    bool ok() const { return ok_; }
    /// False only where this machine cannot have it (no root, a package missing): a test then
    /// skips. Once everything is there, a daemon that does not start is a failure.
    bool available() const { return available_; }
    const std::string& error() const { return error_; }
    /// For `ssh -F`: the generated identity, and only the generated host keys are trusted.
    std::filesystem::path config() const { return dir_ / "ssh_config"; }

  private:
    bool start(const NetworkLab& lab, const std::vector<int>& hosts) {
        for (const char* tool : {"/usr/sbin/sshd", "/usr/bin/ssh", "/usr/bin/ssh-keygen"})
            if (!std::filesystem::exists(tool))
                return unavailable(std::string("no ") + tool +
                                   " (Debian's openssh-server and openssh-client)");
        std::error_code e;
        if (!std::filesystem::exists("/run/sshd")) {
            madeRunDir_ = std::filesystem::create_directories("/run/sshd", e);
            if (e) return fail("cannot make /run/sshd: " + e.message());
        }
        if (!keygen(dir_ / "user_key")) return false;
        std::filesystem::copy_file(dir_ / "user_key.pub", dir_ / "authorized_keys");
        std::ofstream known(dir_ / "known_hosts");
        for (int h : hosts) {
            const std::string n = std::to_string(h), address = NetworkLab::address(h);
            const auto key = dir_ / ("host_key_" + n);
            if (!keygen(key)) return false;
            known << address << ' ' << readFile(key.string() + ".pub");
            const auto config = dir_ / ("sshd_config_" + n);
            std::ofstream(config) << "ListenAddress " << address << ":22\n"
                                  << "HostKey " << key.string() << "\n"
                                  << "PidFile " << (dir_ / ("sshd_" + n + ".pid")).string() << "\n"
                                  << "AuthorizedKeysFile " << (dir_ / "authorized_keys").string()
                                  << "\n"
                                  << "PubkeyAuthentication yes\nPasswordAuthentication no\n"
                                  << "KbdInteractiveAuthentication no\nUsePAM no\n"
                                  << "PermitRootLogin prohibit-password\n"
                                  // The test's folder is under /tmp, which is world-writable.
                                  << "StrictModes no\n";
            const auto log = dir_ / ("sshd_" + n + ".log");
            const pid_t pid =
                spawnProcess(lab.in(h, {"/usr/sbin/sshd", "-D", "-e", "-f", config.string()}), log);
            if (pid < 0) return fail("cannot start sshd on host " + n);
            pids_.push_back(pid);
            if (waitForLine(log, std::regex("Server listening on"), pid, 30).empty())
                return fail("sshd on host " + n + " did not start: " + readFile(log));
        }
        known.close();
        std::ofstream(config()) << "Host *\n"
                                << "  User root\n"
                                << "  IdentityFile " << (dir_ / "user_key").string() << "\n"
                                << "  IdentitiesOnly yes\n"
                                << "  UserKnownHostsFile " << (dir_ / "known_hosts").string()
                                << "\n"
                                << "  GlobalKnownHostsFile /dev/null\n"
                                << "  StrictHostKeyChecking yes\n"
                                << "  LogLevel ERROR\n";
        return true;
    }

    bool keygen(const std::filesystem::path& key) {
        const ProcessResult r = runProcess({"/usr/bin/ssh-keygen", "-q", "-t", "ed25519", "-N", "",
                                            "-C", "igi-test", "-f", key.string()},
                                           dir_ / "ssh-keygen.log", 30);
        if (r.exitCode != 0) fail("ssh-keygen failed: " + r.output);
        return r.exitCode == 0;
    }
    bool unavailable(const std::string& why) {
        available_ = false;
        return fail(why);
    }
    bool fail(const std::string& why) {
        if (error_.empty()) error_ = why;
        return false;
    }

    std::filesystem::path dir_;
    int lock_ = -1;
    std::vector<pid_t> pids_;
    bool madeRunDir_ = false;
    bool ok_ = false;
    bool available_ = true;
    std::string error_;
};

}  // namespace igi::testing
