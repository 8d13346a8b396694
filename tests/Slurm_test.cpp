// deploy/slurm/igi.sbatch on a real, one-machine SLURM (tests/SlurmCluster.h): submitted with
// sbatch as a user would, three tasks on one node.
#include <gtest/gtest.h>

#include "Session.h"
#include "SlurmCluster.h"

namespace igi::testing {
namespace {

namespace fs = std::filesystem;

// Submits the batch script with three tasks and checks the job; the SLURM daemons stop when it
// returns, before the test removes their folder.
void runThreeTaskJob(const fs::path& dir) {
    SlurmCluster slurm(dir / "slurm");
    if (!slurm.ok()) GTEST_SKIP() << "no test SLURM: " << slurm.error();

    // The submit folder: sbatch runs the job there, relative outputs land there.
    const fs::path submit = dir / "submit";
    fs::create_directories(submit);
    const std::string scene = (sourceDir() / "scenes/cornell/cornell.json").string();
    const ProcessResult r = runProcess(
        slurm.with({"/usr/bin/env", "IGI_BIN=" + binDir().string(), "/bin/sh", "-c",
                    "cd \"$0\" && exec /usr/bin/sbatch --wait -n 3 \"$@\"", submit.string(),
                    (sourceDir() / "deploy/slurm/igi.sbatch").string(), "--scene", scene, "--width",
                    "160", "--height", "120", "--frames", "6", "--output", "slurm.exr"}),
        dir / "sbatch.log", 600);
    std::smatch job;
    ASSERT_TRUE(std::regex_search(r.output, job, std::regex(R"(Submitted batch job (\d+))")))
        << r.output;
    const fs::path jobLog = submit / ("igi-" + job[1].str() + ".out");
    ASSERT_EQ(r.exitCode, 0) << r.output << readFile(jobLog) << readFile(dir / "slurm/slurmd.log");

    const std::string log = readFile(jobLog);
    EXPECT_TRUE(
        std::regex_search(log, std::regex(R"(igi.sbatch: master on \S+ \(\S+:\d+\), 2 clients)")))
        << log;
    EXPECT_NE(log.find("2 clients ready"), std::string::npos) << log;
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

// The issue's SLURM test: the master on the first task, two clients by srun, the secret in the
// job's private folder (gone afterwards), outputs in the submit folder, and the image equals a
// local run's.
TEST(Slurm, TheBatchScriptRendersWithThreeTasksLikeALocalRun) {
    const fs::path dir = scratchDir("slurm");
    runThreeTaskJob(dir);
    if (!HasFailure() && !IsSkipped()) fs::remove_all(dir);
}

}  // namespace
}  // namespace igi::testing
