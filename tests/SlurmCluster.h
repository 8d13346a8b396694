#pragma once
// A small SLURM cluster on test hosts (tests/NetworkLab.h): slurmctld and munged on host 0 (the
// login node, where jobs are submitted), one slurmd per compute node on hosts 1..N (nodes
// node1..nodeN at those hosts' addresses), from Debian's packages (munge, slurmctld, slurmd,
// slurm-client). Every file of theirs is in the test's folder (key, munge socket, state, spool,
// logs, pid files). Each node declares 2 CPUs whatever the machine has
// (SlurmdParameters=config_overrides), so that jobs of several tasks per node fit on a 2-core
// machine. The destructor stops the daemons. Commands for it run on host 0 through on(): in
// that host's namespace, with SLURM_CONF set. Needs root (the daemons run as root).

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "NetworkLab.h"
#include "Session.h"

namespace igi::testing {

class SlurmCluster {
  public:
    /// Compute nodes on hosts 1..`nodes` of `lab`.
    SlurmCluster(const NetworkLab& lab, int nodes, const std::filesystem::path& dir)
        : lab_(lab), dir_(dir) {
        ok_ = start(nodes);
    }

    ~SlurmCluster() {
        for (auto it = pids_.rbegin(); it != pids_.rend(); ++it)
            if (kill(*it, SIGTERM) == 0 && waitProcess(*it, 20) < 0) kill(*it, SIGKILL);
    }

    bool ok() const { return ok_; }
    /// False only where this machine cannot have it (no root, a package missing): a test then
    /// skips. Once everything is there, a daemon that does not start is a failure.
    bool available() const { return available_; }
    const std::string& error() const { return error_; }
    std::filesystem::path config() const { return dir_ / "slurm.conf"; }

    /// `command` on the login node (host 0) with SLURM_CONF set for this cluster (through
    /// env(1): spawnProcess passes this process's environment on unchanged).
    std::vector<std::string> on(std::vector<std::string> command) const {
        command.insert(command.begin(), {"/usr/bin/env", "SLURM_CONF=" + config().string()});
        return lab_.in(0, command);
    }

  private:
    bool start(int nodes) {
        if (geteuid() != 0) return unavailable("needs root (slurmd and munged run as root)");
        for (const char* tool : {"/usr/sbin/munged", "/usr/sbin/slurmctld", "/usr/sbin/slurmd",
                                 "/usr/bin/sbatch", "/usr/bin/srun", "/usr/bin/scontrol"})
            if (!std::filesystem::exists(tool))
                return unavailable(std::string("no ") + tool +
                                   " (Debian's munge, slurmctld, slurmd and slurm-client)");
        // slurmctld checks that SlurmctldHost names the machine it runs on.
        char host[256] = {};
        gethostname(host, sizeof host - 1);
        const auto munge = dir_ / "munge";
        for (const char* d : {"munge", "state"}) std::filesystem::create_directories(dir_ / d);
        for (int n = 1; n <= nodes; ++n)
            std::filesystem::create_directories(dir_ / "spool" / ("node" + std::to_string(n)));
        std::filesystem::permissions(munge, std::filesystem::perms::owner_all |
                                                std::filesystem::perms::group_exec |
                                                std::filesystem::perms::others_exec);
        {
            std::ofstream key(munge / "munge.key", std::ios::binary);
            std::ifstream random("/dev/urandom", std::ios::binary);
            std::vector<char> bytes(1024);
            random.read(bytes.data(), std::streamsize(bytes.size()));
            key.write(bytes.data(), std::streamsize(bytes.size()));
        }
        std::filesystem::permissions(munge / "munge.key", std::filesystem::perms::owner_read);
        const std::string socket = (munge / "munge.socket").string();
        if (!spawn({"/usr/sbin/munged", "--foreground", "--force", "--socket=" + socket,
                    "--key-file=" + (munge / "munge.key").string(),
                    "--pid-file=" + (munge / "munged.pid").string(),
                    "--log-file=" + (munge / "munged.log").string(),
                    "--seed-file=" + (munge / "munged.seed").string()},
                   munge / "munged.out", "Created socket"))
            return false;

        const auto d = [&](const char* name) { return (dir_ / name).string(); };
        std::ofstream conf(config());
        // Every daemon has its host's address to itself: the usual ports cannot collide.
        conf << "ClusterName=igitest\n"
             << "SlurmctldHost=" << host << "(" << NetworkLab::address(0) << ")\n"
             << "SlurmctldPort=6817\nSlurmdPort=6818\n"
             << "SlurmUser=root\nSlurmdUser=root\n"
             << "AuthType=auth/munge\nCredType=cred/munge\n"
             << "AuthInfo=socket=" << socket << "\n"
             << "StateSaveLocation=" << d("state") << "\n"
             << "SlurmdSpoolDir=" << d("spool") << "/%n\n"
             << "SlurmctldPidFile=" << d("slurmctld.pid") << "\n"
             << "SlurmdPidFile=" << d("slurmd") << "-%n.pid\n"
             << "SlurmctldLogFile=" << d("slurmctld.log") << "\n"
             << "SlurmdLogFile=" << d("slurmd")
             << "-%n.log\n"
             // No cgroups: plain process tracking, no task binding.
             << "ProctrackType=proctrack/linuxproc\nTaskPlugin=task/none\n"
             << "JobAcctGatherType=jobacct_gather/none\n"
             << "AccountingStorageType=accounting_storage/none\n"
             << "SchedulerType=sched/builtin\n"
             << "SelectType=select/cons_tres\nSelectTypeParameters=CR_CPU\n"
             << "MpiDefault=none\nReturnToService=2\n"
             << "SlurmdParameters=config_overrides\n";
        std::string names;
        for (int n = 1; n <= nodes; ++n) {
            conf << "NodeName=node" << n << " NodeAddr=" << NetworkLab::address(n)
                 << " CPUs=2 State=UNKNOWN\n";
            names += (n > 1 ? "," : "") + ("node" + std::to_string(n));
        }
        conf << "PartitionName=igitest Nodes=" << names
             << " Default=YES MaxTime=INFINITE State=UP\n";
        conf.close();
        if (!spawn(lab_.in(0, {"/usr/sbin/slurmctld", "-D", "-f", config().string()}),
                   dir_ / "slurmctld.out", ""))
            return false;
        for (int n = 1; n <= nodes; ++n)
            if (!spawn(lab_.in(n, {"/usr/sbin/slurmd", "-D", "-f", config().string(), "-N",
                                   "node" + std::to_string(n)}),
                       dir_ / ("slurmd-node" + std::to_string(n) + ".out"), ""))
                return false;
        // Ready when every node is idle: then a job starts at once.
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
        while (std::chrono::steady_clock::now() < deadline) {
            const ProcessResult r =
                runProcess(on({"/usr/bin/sinfo", "-h", "-N", "-o", "%T"}), dir_ / "sinfo.log", 30);
            if (r.exitCode == 0 && countWord(r.output, "idle") == nodes) return true;
            std::this_thread::sleep_for(std::chrono::milliseconds(250));
        }
        return fail("the nodes never became idle: " + readFile(dir_ / "sinfo.log") +
                    readFile(dir_ / "slurmctld.log") + readFile(dir_ / "slurmd-node1.log"));
    }

    static int countWord(const std::string& text, const std::string& word) {
        int n = 0;
        for (auto p = text.find(word); p != std::string::npos; p = text.find(word, p + 1)) ++n;
        return n;
    }

    /// Starts a daemon in the foreground; with `ready`, waits for that text in its output.
    bool spawn(const std::vector<std::string>& command, const std::filesystem::path& log,
               const std::string& ready) {
        const pid_t pid = spawnProcess(command, log);
        if (pid < 0) return fail("cannot start " + command[0]);
        pids_.push_back(pid);
        if (!ready.empty() && waitForLine(log, std::regex(ready), pid, 30).empty())
            return fail(command[0] + " did not start: " + readFile(log));
        return true;
    }

    bool unavailable(const std::string& why) {
        available_ = false;
        return fail(why);
    }
    bool fail(const std::string& why) {
        if (error_.empty()) error_ = why;
        return false;
    }

    const NetworkLab& lab_;
    std::filesystem::path dir_;
    std::vector<pid_t> pids_;
    bool ok_ = false;
    bool available_ = true;
    std::string error_;
};

}  // namespace igi::testing
