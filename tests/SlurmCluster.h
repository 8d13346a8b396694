#pragma once
// A one-machine SLURM for tests: munged, slurmctld and slurmd from Debian's packages (munge,
// slurmctld, slurmd, slurm-client), every file of theirs in the test's folder (key, sockets,
// state, spool, logs, pid files), on loopback ports that were free. The node declares 4 CPUs
// whatever the machine has (SlurmdParameters=config_overrides), so that a job of several tasks
// fits on a 2-core machine. The destructor stops the three daemons. Commands for it need
// environment(): SLURM_CONF pointing at its slurm.conf. Needs root (the daemons run as root).

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "Session.h"

namespace igi::testing {

class SlurmCluster {
  public:
    explicit SlurmCluster(const std::filesystem::path& dir) : dir_(dir) { ok_ = start(); }

    ~SlurmCluster() {
        for (auto it = pids_.rbegin(); it != pids_.rend(); ++it)
            if (kill(*it, SIGTERM) == 0 && waitProcess(*it, 20) < 0) kill(*it, SIGKILL);
    }

    bool ok() const { return ok_; }
    const std::string& error() const { return error_; }
    std::filesystem::path config() const { return dir_ / "slurm.conf"; }

    /// `command` with SLURM_CONF set for this cluster (through env(1): spawnProcess passes this
    /// process's environment on unchanged).
    std::vector<std::string> with(std::vector<std::string> command) const {
        command.insert(command.begin(), {"/usr/bin/env", "SLURM_CONF=" + config().string()});
        return command;
    }

  private:
    bool start() {
        if (geteuid() != 0) return fail("needs root (slurmd and munged run as root)");
        for (const char* tool : {"/usr/sbin/munged", "/usr/sbin/slurmctld", "/usr/sbin/slurmd",
                                 "/usr/bin/sbatch", "/usr/bin/srun", "/usr/bin/scontrol"})
            if (!std::filesystem::exists(tool))
                return fail(std::string("no ") + tool +
                            " (Debian's munge, slurmctld, slurmd and slurm-client)");
        char host[256] = {};
        gethostname(host, sizeof host - 1);
        const std::string node = host;
        const auto munge = dir_ / "munge";
        for (const char* d : {"munge", "state", "spool"})
            std::filesystem::create_directories(dir_ / d);
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
        std::ofstream(config()) << "ClusterName=igitest\n"
                                << "SlurmctldHost=" << node << "(127.0.0.1)\n"
                                << "SlurmctldPort=" << freePort() << "\n"
                                << "SlurmdPort=" << freePort() << "\n"
                                << "SlurmUser=root\nSlurmdUser=root\n"
                                << "AuthType=auth/munge\nCredType=cred/munge\n"
                                << "AuthInfo=socket=" << socket << "\n"
                                << "StateSaveLocation=" << d("state") << "\n"
                                << "SlurmdSpoolDir=" << d("spool") << "\n"
                                << "SlurmctldPidFile=" << d("slurmctld.pid") << "\n"
                                << "SlurmdPidFile=" << d("slurmd.pid") << "\n"
                                << "SlurmctldLogFile=" << d("slurmctld.log") << "\n"
                                << "SlurmdLogFile=" << d("slurmd.log")
                                << "\n"
                                // No cgroups: plain process tracking, no task binding.
                                << "ProctrackType=proctrack/linuxproc\nTaskPlugin=task/none\n"
                                << "JobAcctGatherType=jobacct_gather/none\n"
                                << "AccountingStorageType=accounting_storage/none\n"
                                << "SchedulerType=sched/builtin\n"
                                << "SelectType=select/cons_tres\nSelectTypeParameters=CR_CPU\n"
                                << "MpiDefault=none\nReturnToService=2\n"
                                << "SlurmdParameters=config_overrides\n"
                                << "NodeName=" << node
                                << " NodeAddr=127.0.0.1 CPUs=4 State=UNKNOWN\n"
                                << "PartitionName=igitest Nodes=" << node
                                << " Default=YES MaxTime=INFINITE State=UP\n";
        if (!spawn({"/usr/sbin/slurmctld", "-D", "-f", config().string()}, dir_ / "slurmctld.out",
                   "") ||
            !spawn({"/usr/sbin/slurmd", "-D", "-f", config().string(), "-N", node},
                   dir_ / "slurmd.out", ""))
            return false;
        // Ready when the node is idle: then a job starts at once.
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
        while (std::chrono::steady_clock::now() < deadline) {
            const ProcessResult r =
                runProcess(with({"/usr/bin/sinfo", "-h", "-o", "%T"}), dir_ / "sinfo.log", 30);
            if (r.exitCode == 0 && r.output.find("idle") != std::string::npos) return true;
            std::this_thread::sleep_for(std::chrono::milliseconds(250));
        }
        return fail("the node never became idle: " + readFile(dir_ / "sinfo.log") +
                    readFile(dir_ / "slurmctld.log") + readFile(dir_ / "slurmd.log"));
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

    bool fail(const std::string& why) {
        if (error_.empty()) error_ = why;
        return false;
    }

    std::filesystem::path dir_;
    std::vector<pid_t> pids_;
    bool ok_ = false;
    std::string error_;
};

}  // namespace igi::testing
