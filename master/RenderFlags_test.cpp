#include "RenderFlags.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "scene/RenderSettingsJson.h"
#include "scene/SceneError.h"

namespace igi {
namespace {

std::string messageFor(const nlohmann::json& overrides) {
    RenderSettings s;
    try {
        applyRenderSettingsJson(overrides, s, "command line", "/render");
    } catch (const SceneError& e) {
        return commandLineMessage(e);
    }
    return "";
}

TEST(RenderFlags, NamesTheFlagOfAKey) {
    EXPECT_EQ(flagForRenderKey("path_samples"), "--spp");
    EXPECT_EQ(flagForRenderKey("direct_samples"), "--direct-samples");
    EXPECT_EQ(flagForRenderKey("gi"), "--gi");
    EXPECT_EQ(flagForRenderKey("accumulate"), "--no-accumulate");
}

// Issue 40: `--spp 0` said "command line: /render/path_samples: ...".
TEST(RenderFlags, CommandLineErrorsNameTheFlag) {
    EXPECT_EQ(messageFor({{"path_samples", 0}}), "--spp: must be in [1, 65536], got 0");
    EXPECT_EQ(messageFor({{"interleave", {0, 3}}}), "--interleave: must be in [1, 16], got 0");
    EXPECT_EQ(messageFor({{"spt_pilots", 100}, {"spt_paths", 4}}),
              "--spt-pilots: must be in [1, 4], got 100");
}

}  // namespace
}  // namespace igi
