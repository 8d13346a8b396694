#include "render/TileChannels.h"

#include <gtest/gtest.h>

#include <cmath>

namespace igi {
namespace {

TEST(TileChannels, ResizeAllocatesTheNamedPlanesWithDefaults) {
    TileChannels c;
    c.resize(5, kIrradiance | kDepth);
    EXPECT_EQ(c.count, 5);
    EXPECT_EQ(c.mask(), std::uint32_t(kIrradiance | kDepth));
    ASSERT_EQ(c.irradiance.size(), 5u);
    ASSERT_EQ(c.depth.size(), 5u);
    EXPECT_TRUE(c.reflectance.empty());
    EXPECT_EQ(c.irradiance[4], glm::vec3(0.0f));
    EXPECT_TRUE(std::isinf(c.depth[4]) && c.depth[4] > 0);
}

TEST(TileChannels, ResizeResetsEveryEntryAndDropsUnnamedPlanes) {
    TileChannels c;
    c.resize(3, kAllChannels);
    EXPECT_EQ(c.mask(), kAllChannels);
    c.normal[1] = glm::vec3(0, 1, 0);
    c.depth[1] = 2.0f;
    c.resize(3, kNormal | kDepth);
    EXPECT_EQ(c.mask(), std::uint32_t(kNormal | kDepth));
    EXPECT_EQ(c.normal[1], glm::vec3(0.0f));
    EXPECT_TRUE(std::isinf(c.depth[1]));
    c.resize(0, kAllChannels);
    EXPECT_EQ(c.mask(), 0u);  // no pixels, no planes
    EXPECT_THROW(c.resize(-1, 0), std::invalid_argument);
}

}  // namespace
}  // namespace igi
