#pragma once
// Test "hosts" on one machine: network namespaces joined by veth pairs to a bridge (in a
// namespace of its own, the switch), each host with its own address in 10.213.0.0/24 and its own
// link that a test can rate-limit (tc tbf) or cut (ip link set down). The addresses exist only
// inside these namespaces. Everything is made by the constructor and removed by the destructor
// (deleting a namespace deletes its links and ends nothing else); processes started in a host
// must be ended by the test first. A test killed by a signal runs no destructor: the next lab
// removes what such a test left (namespaces named after a process that no longer exists).
// Needs root and iproute2.

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>
#include <vector>

#include "Process.h"

namespace igi::testing {

class NetworkLab {
  public:
    /// `hosts` hosts, host i at 10.213.0.(i + 1). Check ok() before use: without root, or where
    /// namespaces cannot be made, it is false and error() says why.
    explicit NetworkLab(int hosts, const std::filesystem::path& logDir)
        : prefix_("igi" + std::to_string(getpid()) + "-"), log_(logDir / "network-lab.log") {
        if (geteuid() != 0) {
            error_ = "needs root (network namespaces, veth pairs and a bridge)";
            return;
        }
        removeLeftovers();
        if (!run({"ip", "netns", "add", sw()}) ||
            !run({"ip", "-n", sw(), "link", "add", "br0", "type", "bridge"}) ||
            !run({"ip", "-n", sw(), "link", "set", "br0", "up"}))
            return;
        for (int i = 0; i < hosts; ++i) {
            const std::string ns = host(i), port = "p" + std::to_string(i);
            made_.push_back(ns);
            if (!run({"ip", "netns", "add", ns}) ||
                !run({"ip", "link", "add", "eth0", "netns", ns, "type", "veth", "peer", "name",
                      port, "netns", sw()}) ||
                !run({"ip", "-n", ns, "addr", "add", address(i) + "/24", "dev", "eth0"}) ||
                !run({"ip", "-n", ns, "link", "set", "lo", "up"}) ||
                !run({"ip", "-n", ns, "link", "set", "eth0", "up"}) ||
                !run({"ip", "-n", sw(), "link", "set", port, "master", "br0"}) ||
                !run({"ip", "-n", sw(), "link", "set", port, "up"}))
                return;
        }
        ok_ = true;
    }

    // Not logged: the test may have removed its folder already, and a command whose log cannot
    // be opened does not run at all.
    ~NetworkLab() {
        for (const std::string& ns : made_) run({"ip", "netns", "del", ns}, "/dev/null");
        run({"ip", "netns", "del", sw()}, "/dev/null");
    }

    bool ok() const { return ok_; }
    const std::string& error() const { return error_; }

    std::string host(int i) const { return prefix_ + "h" + std::to_string(i); }
    static std::string address(int i) { return "10.213.0." + std::to_string(i + 1); }

    /// The command, run in host i's network namespace. Through nsenter rather than `ip netns
    /// exec`, which also gives the command a fresh /sys without /sys/fs/cgroup (slurmd fails
    /// without it); the network namespace is all a test host needs.
    std::vector<std::string> in(int i, std::vector<std::string> command) const {
        command.insert(command.begin(), {"/usr/bin/nsenter", "--net=/run/netns/" + host(i)});
        return command;
    }

    /// Host i's link up or down (down: nothing reaches it, nothing leaves it).
    bool setLink(int i, bool up) {
        return run({"ip", "-n", host(i), "link", "set", "eth0", up ? "up" : "down"});
    }

    /// Limits what host i sends to `mbit` Mbit/s (tc's token bucket filter on its link).
    bool limitRate(int i, int mbit) {
        return run({"tc", "-n", host(i), "qdisc", "replace", "dev", "eth0", "root", "tbf", "rate",
                    std::to_string(mbit) + "mbit", "burst", "64kb", "latency", "100ms"});
    }

  private:
    /// Deletes the namespaces of labs whose process is gone ("igi<pid>-...", no /proc/<pid>).
    /// A live process's are left alone, whoever it is: pids are reused, and a lab of another
    /// test running at the same time must keep its hosts.
    void removeLeftovers() {
        std::error_code e;
        for (const auto& entry : std::filesystem::directory_iterator("/run/netns", e)) {
            const std::string name = entry.path().filename().string();
            const std::size_t dash = name.find('-');
            if (name.rfind("igi", 0) != 0 || dash == std::string::npos || dash == 3) continue;
            const std::string pid = name.substr(3, dash - 3);
            const bool digits = std::all_of(pid.begin(), pid.end(),
                                            [](unsigned char c) { return std::isdigit(c); });
            if (digits && !std::filesystem::exists("/proc/" + pid))
                run({"ip", "netns", "del", name}, "/dev/null");
        }
    }

    std::string sw() const { return prefix_ + "sw"; }

    bool run(std::vector<std::string> command) { return run(std::move(command), log_); }

    bool run(std::vector<std::string> command, const std::filesystem::path& log) {
        command[0] = "/sbin/" + command[0];  // iproute2 puts ip and tc there
        const ProcessResult r = runProcess(command, log, 30);
        if (r.exitCode == 0) return true;
        if (error_.empty()) {
            std::string line;
            for (const auto& w : command) line += (line.empty() ? "" : " ") + w;
            error_ = line + " failed (exit " + std::to_string(r.exitCode) + "): " + r.output;
        }
        return false;
    }

    std::string prefix_;
    std::filesystem::path log_;
    std::vector<std::string> made_;
    bool ok_ = false;
    std::string error_;
};

}  // namespace igi::testing
