// The tests' own process helpers (tests/Process.h, tests/Session.h): a process that has ended
// counts as ended even before anyone waits for it. A zombie still answers kill(pid, 0), so a
// wait that asked only that ran to its deadline: the launcher that exited at once cost the
// Cluster tests 180 s each and hid why it had exited.
#include <gtest/gtest.h>

#include "Session.h"

namespace igi::testing {
namespace {

TEST(Process, AChildThatEndedIsNotRunningAndItsExitCodeIsKept) {
    const auto dir = scratchDir("process-ended");
    const pid_t pid = spawnProcess({"/bin/sh", "-c", "echo bye; exit 3"}, dir / "out.log");
    ASSERT_GT(pid, 0);
    // It ends at once; until waited for it stays a zombie, which kill(pid, 0) cannot tell.
    for (int i = 0; i < 500 && processRunning(pid); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    EXPECT_FALSE(processRunning(pid));
    EXPECT_EQ(kill(pid, 0), 0) << "no longer a zombie: the check above reaped it";
    EXPECT_EQ(waitProcess(pid, 10), 3) << "the exit code is still there to collect";
    std::filesystem::remove_all(dir);
}

TEST(Process, ARunningChildIsRunning) {
    const auto dir = scratchDir("process-running");
    const pid_t pid = spawnProcess({"/bin/sleep", "30"}, dir / "out.log");
    ASSERT_GT(pid, 0);
    EXPECT_TRUE(processRunning(pid));
    kill(pid, SIGKILL);
    EXPECT_EQ(waitProcess(pid, 10), 128 + SIGKILL);
    std::filesystem::remove_all(dir);
}

TEST(Process, WaitingForALineEndsWhenTheProcessEndsWithoutIt) {
    const auto dir = scratchDir("process-line");
    const pid_t pid = spawnProcess({"/bin/sh", "-c", "echo something else"}, dir / "out.log");
    ASSERT_GT(pid, 0);
    const auto start = std::chrono::steady_clock::now();
    EXPECT_TRUE(waitForLine(dir / "out.log", std::regex("never printed"), pid, 120).empty());
    // Bounded far below the 120 s deadline: a wait that missed the process's end ran to it.
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(60));
    EXPECT_EQ(waitProcess(pid, 10), 0);
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace igi::testing
