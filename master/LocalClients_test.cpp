#include "LocalClients.h"

#include <algorithm>
#include <mutex>

#include <gtest/gtest.h>

namespace igi {
namespace {

// Under a progress line, what the clients write to stderr reaches the master line by line
// (ProgressLine::printAbove prints it), however the writes are cut, from every client, and the
// pipe's reader ends when the clients do.
TEST(LocalClients, TheirStderrLinesReachTheHandlerWholeFromEveryClient) {
    std::mutex mutex;
    std::vector<std::string> lines;
    {
        LocalClients clients;
        // A line written in two pieces, a whole one, and a last one without its newline; the
        // shell stands in for igi-client (the handler cares only about the bytes).
        clients.start("/bin/sh",
                      {"-c",
                       "printf 'warn: half' >&2; sleep 0.1; printf ' and half\\nnext\\n' >&2; "
                       "printf tail >&2; echo 'on stdout'"},
                      2, {}, [&](const std::string& line) {
                          std::lock_guard lock(mutex);
                          lines.push_back(line);
                      });
        EXPECT_EQ(clients.pids().size(), 2u);
        EXPECT_EQ(clients.stop(10), 0);
        std::lock_guard lock(mutex);
        std::sort(lines.begin(), lines.end());
        // Each client has its own pipe: their pieces never meet inside a line.
        const std::vector<std::string> expected = {
            "next", "next", "tail", "tail", "warn: half and half", "warn: half and half"};
        EXPECT_EQ(lines, expected);
    }
}

TEST(LocalClients, WithoutAHandlerTheyShareTheMastersStderr) {
    LocalClients clients;
    clients.start("/bin/sh", {"-c", "exit 0"}, 1);
    EXPECT_EQ(clients.stop(10), 0);
    EXPECT_TRUE(clients.pids().empty());
}

}  // namespace
}  // namespace igi
