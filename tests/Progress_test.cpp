// The terminal's progress line (master/ProgressLine.h): drawn on a terminal, absent in a log.
#include <gtest/gtest.h>

#include "Session.h"

namespace igi::testing {
namespace {

std::string quoted(const std::vector<std::string>& args) {
    std::string line;
    for (const std::string& a : args) line += (line.empty() ? "'" : " '") + a + "'";
    return line;
}

TEST(Progress, ATerminalGetsAProgressLineAndALogGetsFrameLines) {
    const auto dir = scratchDir("progress");
    auto args = sceneArgs(3);
    args.insert(args.end(), {"--local-clients", "1"});
    // util-linux's script runs the master on a pseudo-terminal and copies what it draws.
    const ProcessResult tty = runProcess(
        {"/usr/bin/script", "-qec", quoted(masterCommand(args)), (dir / "typescript").string()},
        dir / "tty.log");
    ASSERT_EQ(tty.exitCode, 0) << tty.output;
    EXPECT_NE(tty.output.find("\r\033[Kframe 3/3 [====================]"), std::string::npos)
        << tty.output;
    EXPECT_NE(tty.output.find("frame 1/3 ["), std::string::npos) << tty.output;
    // The frame lines are the progress line's job there; the log lines still print above it.
    const std::regex frameLine(R"(frame +\d+:)");
    EXPECT_FALSE(std::regex_search(tty.output, frameLine)) << tty.output;
    EXPECT_NE(tty.output.find("3 frames in"), std::string::npos) << tty.output;

    const ProcessResult log = runProcess(masterCommand(args), dir / "plain.log");
    ASSERT_EQ(log.exitCode, 0) << log.output;
    EXPECT_EQ(log.output.find("frame 3/3"), std::string::npos) << log.output;
    EXPECT_EQ(log.output.find('\r'), std::string::npos);
    EXPECT_TRUE(std::regex_search(log.output, frameLine)) << log.output;
    EXPECT_NE(log.output.find("3 frames in"), std::string::npos) << log.output;
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace igi::testing
