// igi-bench (tools/bench_main.cpp) holds a few tiles at a time, as a session's client does: the
// client's figures count the same rays whichever number of tiles it holds, every tile of every
// frame rendered once. Real process, its JSON read back.
#include <filesystem>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "Process.h"

namespace igi {
namespace {

using namespace igi::testing;
namespace fs = std::filesystem;

/// igi-bench's JSON on the default scene at 96 x 72, 2 threads, with `tilesInFlight` (0: the
/// default); a discarded value if it failed.
nlohmann::json bench(const fs::path& dir, int tilesInFlight) {
    const std::string name = "bench-" + std::to_string(tilesInFlight);
    const ProcessResult r =
        runProcess({(binDir() / "igi-bench").string(), "--scene",
                    (sourceDir() / "scenes/cornell/cornell.json").string(), "--threads", "2",
                    "--frames", "2", "--segments", "20000", "--width", "96", "--height", "72",
                    "--tiles-in-flight", std::to_string(tilesInFlight)},
                   dir / (name + ".log"), 300);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    // The log holds stderr too: the JSON is the block from the first line that opens it.
    const auto start = r.output.find("\n{");
    const std::string json = r.output.substr(r.output.front() == '{' ? 0 : start + 1);
    return nlohmann::json::parse(json, nullptr, false);
}

TEST(Bench, TheClientsRaysDoNotDependOnTheTilesItHolds) {
    const fs::path dir = scratchDir("bench_tiles_in_flight");
    const nlohmann::json one = bench(dir, 1), usual = bench(dir, 0), all = bench(dir, 100000);
    for (const auto* j : {&one, &usual, &all}) ASSERT_TRUE(j->is_object()) << j->dump();
    EXPECT_EQ(one["client_tiles_in_flight"], 1);
    EXPECT_EQ(usual["client_tiles_in_flight"], 2);  // 2 + threads / 8 with 2 threads
    EXPECT_GT(one["client_shadow_rays"].get<double>(), 0);
    for (const auto* j : {&usual, &all}) {
        EXPECT_EQ((*j)["client_rays"], one["client_rays"]);
        EXPECT_EQ((*j)["client_shadow_rays"], one["client_shadow_rays"]);
    }
    fs::remove_all(dir);
}

}  // namespace
}  // namespace igi
