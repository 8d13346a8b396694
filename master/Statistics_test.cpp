#include "Statistics.h"

#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace igi {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
    const fs::path dir =
        fs::temp_directory_path() / ("igi-stats-" + name + "-" + std::to_string(getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

/// One frame of two tiles, the first from client 1 (set 0), the second from client 2 (sets 0
/// and 1), shown.
void renderFrame(Statistics& stats, std::uint32_t f) {
    proto::TileStats tile;
    tile.rays = 100;
    tile.vpls = 10;
    stats.noteAssignment(f, 1, 0);
    stats.noteAssignment(f, 2, 0);
    stats.noteAssignment(f, 2, 1);
    stats.addTile(f, 1, tile, 50, 64);
    stats.addTile(f, 2, tile, 50, 64);
    stats.frame(f).shown = true;
}

// Issue 39: every frame's statistics and every client's sets of every frame were kept until the
// end, about 0.9 KB a frame with two clients, for a session of days. Now a frame is written
// when it closes: the JSON file is the same as when everything was kept.
TEST(Statistics, FramesAreWrittenAsTheyCloseAndTheFileKeepsItsSchema) {
    const fs::path dir = scratch("schema");
    const fs::path path = dir / "stats.json";
    {
        Statistics stats;
        stats.client(1).threads = 2;
        stats.client(2).threads = 2;
        stats.streamFramesFor(path);
        for (std::uint32_t f = 0; f < 5; ++f) {
            renderFrame(stats, f);
            // A settings command's settings, in force from frame 3.
            if (f == 3) stats.frame(f).settings = R"({"indirect_vpls":64})";
            stats.closeFrame(f);
        }
        // A late copy of a closed frame's tile counts for its client only.
        stats.addDuplicate(2, 1, 40);
        // Frame 5 is open when the session ends: its client sets count, the frame does not.
        stats.noteAssignment(5, 1, 2);
        EXPECT_TRUE(fs::exists(Statistics::framesFile(path)));
        stats.writeJson(path, {{"scene", "test"}}, 0.0, 2.0);
        EXPECT_FALSE(fs::exists(Statistics::framesFile(path))) << "the sidecar is removed";
    }
    std::ifstream in(path);
    const nlohmann::json j = nlohmann::json::parse(in);
    ASSERT_EQ(j["frames"].size(), 5u);
    for (int f = 0; f < 5; ++f) {
        EXPECT_EQ(j["frames"][f]["index"], f);
        EXPECT_EQ(j["frames"][f]["rays"], 200);
        EXPECT_EQ(j["frames"][f]["tiles"], 2);
        EXPECT_EQ(j["frames"][f]["pixels"], 128);
        EXPECT_DOUBLE_EQ(j["frames"][f]["vpls"], 10.0);
    }
    EXPECT_EQ(j["frames"][2]["duplicate_tiles"], 0) << "written before the late copy came";
    EXPECT_EQ(j["frames"][3]["settings"]["indirect_vpls"], 64);
    EXPECT_FALSE(j["frames"][2].contains("settings")) << "only where the settings changed";
    EXPECT_DOUBLE_EQ(j["fps"], 2.5);
    EXPECT_DOUBLE_EQ(j["seconds"], 2.0);
    EXPECT_EQ(j["session"]["scene"], "test");
    ASSERT_EQ(j["clients"].size(), 2u);
    const nlohmann::json& one = j["clients"][0];
    const nlohmann::json& two = j["clients"][1];
    EXPECT_EQ(one["frames"], 6);
    EXPECT_EQ(one["first_frame"], 0);
    EXPECT_DOUBLE_EQ(one["distinct_sets_per_frame"], 1.0);
    EXPECT_EQ(one["bytes"], 5 * 50 + 40);
    EXPECT_EQ(two["frames"], 5);
    EXPECT_DOUBLE_EQ(two["distinct_sets_per_frame"], 2.0);
    EXPECT_EQ(two["tiles"], 5);
    fs::remove_all(dir);
}

TEST(Statistics, ASessionThatEndsInAnErrorLeavesNoSidecar) {
    const fs::path dir = scratch("error");
    {
        Statistics stats;
        stats.streamFramesFor(dir / "stats.json");
        renderFrame(stats, 0);
        stats.closeFrame(0);
    }
    EXPECT_FALSE(fs::exists(Statistics::framesFile(dir / "stats.json")));
    EXPECT_FALSE(fs::exists(dir / "stats.json"));
    fs::remove_all(dir);
}

TEST(Statistics, ASessionWithNoFrameWritesAnEmptyList) {
    const fs::path dir = scratch("empty");
    Statistics stats;
    stats.writeJson(dir / "stats.json", nlohmann::json::object(), 0.0, 0.0);
    std::ifstream in(dir / "stats.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_TRUE(j["frames"].is_array());
    EXPECT_TRUE(j["frames"].empty());
    EXPECT_TRUE(j["clients"].empty());
    fs::remove_all(dir);
}

}  // namespace
}  // namespace igi
