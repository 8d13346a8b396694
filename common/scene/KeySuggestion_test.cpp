#include "scene/KeySuggestion.h"

#include <gtest/gtest.h>

namespace igi {
namespace {

// Issue 40: `"spp": 4` in "render" was refused without naming path_samples.
TEST(KeySuggestion, FindsTheKeyMeant) {
    EXPECT_EQ(suggestKey("spp", {"path_samples", "seed"}), "path_samples");
    EXPECT_EQ(suggestKey("direct-samples", {"direct_samples", "vpl_paths"}), "direct_samples");
    EXPECT_EQ(suggestKey("Seed", {"direct_samples", "seed"}), "seed");
    EXPECT_EQ(suggestKey("transfrom", {"file", "transform", "name"}), "transform");
    EXPECT_EQ(suggestKey("indirect_vpl", {"indirect_vpls", "vpl_pool"}), "indirect_vpls");
}

TEST(KeySuggestion, SuggestsNothingFarOrAmbiguous) {
    EXPECT_EQ(suggestKey("banana", {"path_samples", "seed"}), std::nullopt);
    EXPECT_EQ(suggestKey("spp", {"seed"}), std::nullopt) << "its synonym is not a key here";
    EXPECT_EQ(suggestKey("ab", {"ac", "ad"}), std::nullopt);
}

}  // namespace
}  // namespace igi
