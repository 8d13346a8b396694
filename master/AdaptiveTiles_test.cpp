#include "AdaptiveTiles.h"

#include <algorithm>
#include <random>

#include <gtest/gtest.h>

#include "ByteReader.h"
#include "ChannelCodec.h"
#include "FrameCompositor.h"
#include "TestTiles.h"

namespace igi {
namespace {

constexpr int kW = 48, kH = 36, kN = 3, kM = 3, kTileSize = 4;  // 12 regions of 12 x 12

void randomFrame(proto::CodedFrame& frame, const std::vector<Tile>& tiles, std::mt19937& rng) {
    proto::test::RandomTiles random;
    random.extremeScales = false;
    const auto wire = random.encoded(tiles, kN, kM, rng);
    frame.reuse(kW, kH, kN, kM, kTileSize);
    for (std::size_t i = 0; i < tiles.size(); ++i) {
        proto::ByteReader in(wire[i], "TileResult");
        frame.scatter(tiles[i], proto::readTileCodes(in));
    }
}

struct Fixture {
    std::vector<Tile> tiles = makeTiles(kW, kH, kN, kM, kTileSize);
    RenderSettings settings = [] {
        RenderSettings s;
        s.interleaveX = kN, s.interleaveY = kM, s.tileSize = kTileSize;
        return s;
    }();
    ThreadPool pool{2};
    FrameCompositor compositor{kW, kH, settings, pool};
    AdaptiveTiles adaptive{tiles, kW, kH, kN, kM, kTileSize, 3};
    std::mt19937 rng{6};
    proto::CodedFrame frame;

    void accumulate(int frames) {
        for (int f = 0; f < frames; ++f) {
            randomFrame(frame, tiles, rng);
            compositor.composite(frame);
        }
    }
    /// Each region's estimate, in the regions' order (what ShownError hands the decision).
    std::vector<double> regionErrors() const {
        std::vector<double> e;
        for (int r = 0; r < adaptive.regions().count(); ++r)
            e.push_back(compositor.estimatedRelMse(adaptive.regions().rectangle(r)));
        return e;
    }
    /// The same, sorted.
    std::vector<double> estimates() const {
        std::vector<double> e = regionErrors();
        std::sort(e.begin(), e.end());
        return e;
    }
};

// A decision is for the frame `lag` frames after the one composited, and only for its epoch;
// without a target, or before 16 frames, every region is rendered.
TEST(AdaptiveTiles, RegionsAboveTheTargetAreRenderedLagFramesLater) {
    Fixture x;
    x.accumulate(AdaptiveTiles::kMinFrames - 1);
    const double some = x.estimates()[6];
    x.adaptive.decide(20, 1, AdaptiveTiles::kMinFrames - 1, some, x.regionErrors());
    EXPECT_TRUE(x.adaptive.regionsFor(23, 1).all()) << "too few frames to judge a region";
    x.accumulate(1);
    x.adaptive.decide(20, 1, AdaptiveTiles::kMinFrames, 0.0, x.regionErrors());
    EXPECT_TRUE(x.adaptive.regionsFor(23, 1).all()) << "no target";
    EXPECT_THROW(x.adaptive.decide(20, 1, AdaptiveTiles::kMinFrames, 1.0, {0.5, 0.5}),
                 std::logic_error);

    const auto e = x.estimates();
    const double target = (e[5] + e[6]) / 2;  // half the regions are at or below it
    x.adaptive.decide(20, 1, AdaptiveTiles::kMinFrames, target, x.regionErrors());
    const TileRegions regions = x.adaptive.regionsFor(23, 1);
    EXPECT_EQ(regions.renderedCount(), 6);
    for (int r = 0; r < regions.count(); ++r)
        EXPECT_EQ(regions.rendered(r), x.compositor.estimatedRelMse(regions.rectangle(r)) > target);
    EXPECT_TRUE(x.adaptive.regionsFor(22, 1).all()) << "decided for frame 23 only";
    EXPECT_TRUE(x.adaptive.regionsFor(23, 2).all()) << "another epoch starts afresh";
    // Per tile: each of a region's n x m tiles follows it.
    const std::vector<bool> leftOut = x.adaptive.tilesLeftOut(regions);
    ASSERT_EQ(leftOut.size(), x.tiles.size());
    EXPECT_EQ(std::count(leftOut.begin(), leftOut.end(), true), 6 * kN * kM);
    for (std::size_t i = 0; i < leftOut.size(); ++i)
        EXPECT_EQ(leftOut[i], !regions.rendered(regions.regionOf(x.tiles[i])));

    // A target every region meets would leave nothing to render: such a frame renders all.
    x.adaptive.decide(21, 1, AdaptiveTiles::kMinFrames, e.back() * 2, x.regionErrors());
    EXPECT_TRUE(x.adaptive.regionsFor(24, 1).all());
    x.adaptive.forgetBefore(24);
    EXPECT_TRUE(x.adaptive.regionsFor(23, 1).all()) << "forgotten";
}

// The cells a left-out region shows the discontinuity buffer are those of the frame that last
// rendered it: kept when the next frame leaves it out, put back into every frame that does.
TEST(AdaptiveTiles, LeftOutRegionsGetTheCellsOfTheirLastRenderedFrame) {
    Fixture x;
    TileRegions next(kW, kH, kN, kM, kTileSize), all = next;
    next.setRendered(4, false);
    proto::CodedFrame last, later;
    randomFrame(last, x.tiles, x.rng);
    x.adaptive.prepareCells(last, all, next);  // keeps region 4 of `last`
    randomFrame(later, x.tiles, x.rng);
    x.adaptive.prepareCells(later, next, next);
    FrameRow got, fromLast;
    int compared = 0;
    for (int y = 0; y < kH; ++y) {
        later.decodeRow(y, got);
        last.decodeRow(y, fromLast);
        for (int x0 = 0; x0 < kW; ++x0) {
            if (all.regionAt(x0, y) != 4) continue;
            const int i = later.order().position(x0);
            for (int p = FrameRow::kDepth; p <= FrameRow::kUb; ++p)
                EXPECT_EQ(got[p][i], fromLast[p][i]) << x0 << ", " << y << " plane " << p;
            ++compared;
        }
    }
    EXPECT_EQ(compared, 12 * 12);
}

}  // namespace
}  // namespace igi
