// deploy/slurm/igi.sbatch on a real SLURM (tests/SlurmCluster.h) on test hosts
// (tests/NetworkLab.h): submitted with sbatch from the login host as a user would, to two
// compute nodes, three tasks.
#include <gtest/gtest.h>

#include "NetworkLab.h"
#include "Session.h"
#include "SlurmCluster.h"

namespace igi::testing {
namespace {

namespace fs = std::filesystem;

// Submits the batch script with `sbatch -N 2 -n 3` and checks the job; the SLURM daemons stop
// when it returns, before the test removes their folder.
void runJobOnTwoNodes(const fs::path& dir) {
    NetworkLab lab(3, dir);
    if (!lab.ok()) GTEST_SKIP() << "no test hosts: " << lab.error();
    SlurmCluster slurm(lab, 2, dir / "slurm");
    if (!slurm.available()) GTEST_SKIP() << "no test SLURM: " << slurm.error();
    ASSERT_TRUE(slurm.ok()) << "the test SLURM did not start: " << slurm.error();

    // The submit folder: sbatch runs the job there, relative outputs land there.
    const fs::path submit = dir / "submit";
    fs::create_directories(submit);
    const std::string scene = (sourceDir() / "scenes/cornell/cornell.json").string();
    const ProcessResult r = runProcess(
        slurm.on({"/usr/bin/env", "IGI_BIN=" + binDir().string(), "/bin/sh", "-c",
                  "cd \"$0\" && exec /usr/bin/sbatch --wait -N 2 -n 3 \"$@\"", submit.string(),
                  (sourceDir() / "deploy/slurm/igi.sbatch").string(), "--scene", scene, "--width",
                  "160", "--height", "120", "--frames", "6", "--output", "slurm.exr"}),
        dir / "sbatch.log", 600);
    std::smatch job;
    ASSERT_TRUE(std::regex_search(r.output, job, std::regex(R"(Submitted batch job (\d+))")))
        << r.output;
    const fs::path jobLog = submit / ("igi-" + job[1].str() + ".out");
    ASSERT_EQ(r.exitCode, 0) << r.output << readFile(jobLog)
                             << readFile(dir / "slurm/slurmd-node1.log");

    const std::string log = readFile(jobLog);
    EXPECT_TRUE(
        std::regex_search(log, std::regex(R"(igi.sbatch: master on \S+ \(\S+:\d+\), 2 clients)")))
        << log;
    EXPECT_NE(log.find("2 clients ready"), std::string::npos) << log;
    // The master on node 1 (host 1); one client beside it (several tasks on one node), one on
    // node 2 (host 2), each connecting from its node's address.
    EXPECT_NE(log.find("igi.sbatch: master on node1 (" + NetworkLab::address(1) + ":"),
              std::string::npos)
        << log;
    for (int h = 1; h <= 2; ++h)
        EXPECT_NE(log.find("connected from " + NetworkLab::address(h) + ":"), std::string::npos)
            << log;
    // srun --label: the clients are the client step's tasks 0 and 1.
    for (const char* task : {"0: ", "1: "})
        EXPECT_NE(log.find(std::string(task) + "["), std::string::npos) << log;
    EXPECT_FALSE(fs::exists(submit / (".igi-job-" + job[1].str())))
        << "the job's private folder (with the secret) outlived the job";

    auto local = sceneArgs(6);
    local.insert(local.end(), {"--local-clients", "1", "--output", (dir / "local.exr").string()});
    const ProcessResult l = runProcess(masterCommand(local), dir / "local.log");
    ASSERT_EQ(l.exitCode, 0) << l.output;
    expectSameImage(submit / "slurm.exr", dir / "local.exr");
}

// The issue's SLURM test: the master on the first task, two clients by srun (one on each node),
// the secret in the job's private folder (gone afterwards), outputs in the submit folder, and
// the image equals a local run's.
TEST(Slurm, TheBatchScriptRendersOnTwoNodesLikeALocalRun) {
    const fs::path dir = scratchDir("slurm");
    runJobOnTwoNodes(dir);
    if (!HasFailure() && !IsSkipped()) fs::remove_all(dir);
}

}  // namespace
}  // namespace igi::testing
