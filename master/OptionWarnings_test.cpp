#include "OptionWarnings.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace igi {
namespace {

std::string joined(const std::vector<std::string>& lines) {
    std::string out;
    for (const auto& l : lines) out += l + "\n";
    return out;
}

MasterOptions withOutput() {
    MasterOptions o;
    o.outputs = {"out.png"};
    return o;
}

// Issue 40: options that did nothing passed silently.
TEST(OptionWarnings, SequenceFramesWithoutASequenceOrPastTheRun) {
    MasterOptions o = withOutput();
    o.sequenceFrames = {1, 2};
    EXPECT_EQ(joined(uselessOptionWarnings(o, nlohmann::json::object(), {})),
              "--sequence-frames does nothing without --output-sequence\n");
    o.outputSequence = "f_%d.png";
    o.frames = 2;
    o.sequenceFrames = {0, 1, 2, 7};
    EXPECT_EQ(joined(uselessOptionWarnings(o, nlohmann::json::object(), {})),
              "--sequence-frames 2, 7: past the last frame (--frames 2 renders frames 0 to 1), "
              "never written\n");
    o.frames = 0;  // until stopped: any frame may come
    EXPECT_TRUE(uselessOptionWarnings(o, nlohmann::json::object(), {}).empty());
}

TEST(OptionWarnings, SettingsThatTheIntegratorOrModeIgnores) {
    RenderSettings igi;
    EXPECT_EQ(joined(uselessOptionWarnings(withOutput(), {{"path_samples", 4}}, igi)),
              "--spp sets the path tracer's samples; IGI ignores it (--integrator path)\n");
    RenderSettings path;
    path.integrator = IntegratorKind::Path;
    path.gi = GiMode::PhotonMap;
    EXPECT_EQ(joined(uselessOptionWarnings(withOutput(),
                                           {{"gi", "photonmap"}, {"integrator", "path"}}, path)),
              "--gi photonmap does nothing with --integrator path (the path tracer has no GI "
              "mode)\n");
    RenderSettings cache;
    cache.gi = GiMode::Cache;
    EXPECT_EQ(
        joined(uselessOptionWarnings(
            withOutput(), {{"spt_groups", 4}, {"cache_spacing", 0.1}, {"gi", "cache"}}, cache)),
        "--spt-groups does nothing with --gi cache\n");
    EXPECT_EQ(joined(uselessOptionWarnings(withOutput(), {{"first_frame_divisor", 2}}, cache)),
              "--first-frame-divisor does nothing with --gi cache\n");
    EXPECT_TRUE(uselessOptionWarnings(withOutput(), {{"direct_samples", 2}}, igi).empty());
    EXPECT_TRUE(uselessOptionWarnings(withOutput(), {{"first_frame_divisor", 2}}, igi).empty());
}

TEST(OptionWarnings, AFiniteRunThatWritesNothing) {
    MasterOptions o;
    o.frames = 30;
    EXPECT_EQ(joined(uselessOptionWarnings(o, nlohmann::json::object(), {})),
              "no --output (nor --output-sequence): the image of this run is written nowhere\n");
    o.outputSequence = "f_%d.png";
    EXPECT_TRUE(uselessOptionWarnings(o, nlohmann::json::object(), {}).empty());
    o = {};
    o.frames = 0;  // a live session, watched or snapshotted
    EXPECT_TRUE(uselessOptionWarnings(o, nlohmann::json::object(), {}).empty());
}

}  // namespace
}  // namespace igi
