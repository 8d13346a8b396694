// Issue 37, item 3: adaptive tiles. With --target-error, tile regions whose estimated error is
// at or below the target are not rendered again until something changes; the image still does
// not depend on which client rendered what. Real processes on real sockets.
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "Session.h"

namespace igi {
namespace {

using namespace igi::testing;
namespace fs = std::filesystem;

std::string exact(double v) {
    std::ostringstream text;
    text << std::setprecision(17) << v;
    return text.str();
}

/// The Cornell box at 160 x 120 in tiles of 8 (regions of 24 x 24 pixels: 35 of them), with
/// `clients` local clients, for at most `frames` frames, and `extra`; its statistics.
nlohmann::json render(const fs::path& dir, const std::string& name, int clients, int frames,
                      const std::vector<std::string>& extra) {
    auto args = sceneArgs(frames);
    args.insert(args.end(),
                {"--local-clients", std::to_string(clients), "--tile-size", "8", "--stats-json",
                 (dir / (name + ".json")).string(), "--output", (dir / (name + ".exr")).string()});
    args.insert(args.end(), extra.begin(), extra.end());
    const ProcessResult r = runProcess(masterCommand(args), dir / (name + ".log"), 600);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    return readJson(dir / (name + ".json"));
}

/// Each frame's field `key` (0 where absent).
std::vector<double> column(const nlohmann::json& stats, const std::string& key) {
    std::vector<double> v;
    for (const auto& f : stats["frames"])
        v.push_back(f.contains(key) && f[key].is_number() ? f[key].get<double>() : 0.0);
    return v;
}

double sum(const std::vector<double>& v) {
    double s = 0;
    for (const double x : v) s += x;
    return s;
}

// The estimate of a free run after `frames` frames.
double freeEstimate(const fs::path& dir, int frames) {
    const nlohmann::json free = render(dir, "free", 1, frames, {});
    const auto e = column(free, "estimated_rel_mse");
    EXPECT_EQ(e.size(), std::size_t(frames));
    return e.empty() ? 0.0 : e.back();
}

TEST(AdaptiveTiles, RegionsUnderTheTargetAreLeftOutTheSameWithOneAndThreeClients) {
    const fs::path dir = scratchDir("adaptive-tiles");
    // The target: the free run's estimate after 48 frames. The easier regions reach it sooner.
    const double target = freeEstimate(dir, 48);
    ASSERT_GT(target, 0.0);
    const std::vector<std::string> withTarget = {"--target-error", exact(target)};
    const nlohmann::json one = render(dir, "one", 1, 400, withTarget);
    const nlohmann::json three = render(dir, "three", 3, 400, withTarget);
    // Whoever rendered which tile, the same image, and the same regions left out frame by
    // frame: the decisions rest on the composited image alone.
    expectSameImage(dir / "one.exr", dir / "three.exr");
    const auto leftOut = column(one, "tiles_left_out");
    EXPECT_EQ(leftOut, column(three, "tiles_left_out"));
    EXPECT_GT(sum(leftOut), 0.0) << "no region reached the target before the image did";
    // A frame renders every tile but those left out; none before the estimate has 16 frames
    // (AdaptiveTiles::kMinFrames) and the frames already open then (at most 4).
    const auto tiles = column(one, "tiles");
    ASSERT_FALSE(tiles.empty());
    const double all = tiles.front();
    for (std::size_t f = 0; f < tiles.size(); ++f) {
        EXPECT_EQ(tiles[f] + leftOut[f], all) << "frame " << f;
        if (f < 17) {
            EXPECT_EQ(leftOut[f], 0.0) << "frame " << f;
        }
    }
    const auto estimates = column(one, "estimated_rel_mse");
    EXPECT_LE(estimates.back(), target) << "the session ends at the target";

    // Without adaptive tiles every tile is rendered, and the image differs.
    const nlohmann::json plain =
        render(dir, "plain", 1, 400, {"--target-error", exact(target), "--no-adaptive-tiles"});
    EXPECT_EQ(sum(column(plain, "tiles_left_out")), 0.0);
    const Image a = readFiniteImage(dir / "one.exr"), b = readFiniteImage(dir / "plain.exr");
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) differ += a.pixels[i] != b.pixels[i];
    EXPECT_GT(differ, a.pixels.size() / 20) << "adaptive tiles changed nothing";
    fs::remove_all(dir);
}

TEST(AdaptiveTiles, ASceneChangeRendersEveryTileAgain) {
    const fs::path dir = scratchDir("adaptive-change");
    // A target the image cannot reach in the 30 frames before the change nor in the 30 after
    // it (the free run's estimate after 40 frames), which easier regions reach before it.
    const double target = freeEstimate(dir, 40);
    ASSERT_GT(target, 0.0);
    // The glass ball moves at frame 30: a new epoch.
    {
        std::ofstream out(dir / "move.json");
        out << R"({"objects": {"glass_ball": [
            {"frame": 0, "translate": [0.42, 0.36, 0.3], "scale": 0.36},
            {"frame": 29, "translate": [0.42, 0.36, 0.3], "scale": 0.36},
            {"frame": 30, "translate": [0.2, 0.36, 0.3], "scale": 0.36}]}})";
    }
    const std::vector<std::string> extra = {"--target-error", exact(target), "--animation",
                                            (dir / "move.json").string()};
    const nlohmann::json one = render(dir, "one", 1, 60, extra);
    const nlohmann::json three = render(dir, "three", 3, 60, extra);
    expectSameImage(dir / "one.exr", dir / "three.exr");
    const auto leftOut = column(one, "tiles_left_out"), epochs = column(one, "epoch");
    ASSERT_EQ(leftOut.size(), 60u) << "the target was met: " << one.dump();
    EXPECT_EQ(leftOut, column(three, "tiles_left_out"));
    double before = 0;
    for (int f = 0; f < 30; ++f) before += leftOut[std::size_t(f)];
    EXPECT_GT(before, 0.0) << "no region was left out before the change";
    ASSERT_NE(epochs[29], epochs[30]) << "the move is a new epoch";
    // Every tile again from the change until the new accumulation has its 16 frames.
    for (int f = 30; f < 30 + 16; ++f) EXPECT_EQ(leftOut[std::size_t(f)], 0.0) << "frame " << f;
    fs::remove_all(dir);
}

}  // namespace
}  // namespace igi
