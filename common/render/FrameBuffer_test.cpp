#include "render/FrameBuffer.h"

#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

namespace igi {
namespace {

constexpr int kW = 19, kH = 14, kN = 3, kM = 3, kTileSize = 2;

/// Tile results whose planes name the pixel and the frame, with the planes of `mask` only.
TileChannels channelsFor(const Tile& t, std::uint32_t mask, float frame) {
    TileChannels c;
    c.resize(t.pixelCount(kN, kM), mask);
    for (int i = 0; i < c.count; ++i) {
        const float v = frame * 1000.0f + float(t.pixelY(i, kN, kM) * kW + t.pixelX(i, kN));
        if (mask & kIrradiance) c.irradiance[i] = glm::vec3(v, 1, 2);
        if (mask & kReflectance) c.reflectance[i] = glm::vec3(0.5f);
        if (mask & kNormal) c.normal[i] = glm::vec3(0, 0, 1);
        if (mask & kDepth) c.depth[i] = 1.0f + v;
        if (mask & kUnfiltered) c.unfiltered[i] = glm::vec3(v);
        if (mask & kGlossy) c.glossy[i] = glm::vec3(v + 0.5f);
    }
    return c;
}

void scatterFrame(FrameBuffer& f, float frame, std::uint32_t maskEven, std::uint32_t maskOdd) {
    const auto tiles = makeTiles(kW, kH, kN, kM, kTileSize);
    for (std::size_t i = 0; i < tiles.size(); ++i)
        f.scatter(tiles[i], kN, kM, channelsFor(tiles[i], i % 2 ? maskOdd : maskEven, frame));
}

bool samePlanes(const FrameBuffer& a, const FrameBuffer& b) {
    auto same = [](const auto& x, const auto& y) {
        return x.size() == y.size() &&
               std::memcmp(x.data(), y.data(), x.size() * sizeof(x[0])) == 0;
    };
    return same(a.irradiance, b.irradiance) && same(a.reflectance, b.reflectance) &&
           same(a.normal, b.normal) && same(a.depth, b.depth) && same(a.unfiltered, b.unfiltered) &&
           same(a.glossy, b.glossy);
}

// A reused buffer is not cleared: every pixel must be overwritten by its tile, also where a
// tile leaves a plane out that an earlier frame's tile had sent there.
TEST(FrameBuffer, AReusedBufferEqualsAFreshOne) {
    const std::uint32_t all = kAllChannels, noGlossy = kAllChannels & ~kGlossy,
                        bare = kReflectance | kNormal | kDepth;
    FrameBuffer reused;
    reused.reuse(kW, kH);
    EXPECT_EQ(reused.live.bits.load(), 0u);
    scatterFrame(reused, 1, all, noGlossy);   // glossy and unfiltered on some tiles
    scatterFrame(reused, 2, bare, noGlossy);  // then gone from half of them
    reused.reuse(kW, kH);
    scatterFrame(reused, 3, bare, bare);  // and from all
    FrameBuffer fresh;
    fresh.reset(kW, kH);
    scatterFrame(fresh, 3, bare, bare);
    EXPECT_TRUE(samePlanes(reused, fresh));
    for (const glm::vec3& g : reused.glossy) ASSERT_EQ(g, glm::vec3(0.0f));
    for (float d : reused.depth) ASSERT_TRUE(std::isfinite(d));
}

// Planes no tile ever sent stay dead: neither written nor read, and zero.
TEST(FrameBuffer, PlanesNoTileSentStayDead) {
    FrameBuffer f;
    f.reuse(kW, kH);
    scatterFrame(f, 1, kAllChannels & ~kGlossy, kReflectance | kNormal | kDepth);
    EXPECT_FALSE(f.live.has(kGlossy));
    EXPECT_TRUE(f.live.has(kUnfiltered));
    EXPECT_TRUE(f.live.has(kIrradiance));
    for (const glm::vec3& g : f.glossy) ASSERT_EQ(g, glm::vec3(0.0f));
    // A new size starts over.
    f.reuse(kW + 1, kH);
    EXPECT_EQ(f.live.bits.load(), 0u);
    EXPECT_EQ(f.depth.size(), std::size_t(kW + 1) * kH);
}

}  // namespace
}  // namespace igi
