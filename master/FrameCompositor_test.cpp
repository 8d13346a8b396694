#include "FrameCompositor.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <random>

#include <gtest/gtest.h>

#include "ByteReader.h"
#include "ChannelCodec.h"
#include "TestTiles.h"
#include "render/Accumulator.h"
#include "render/DiscontinuityFilter.h"

namespace igi {
namespace {

/// The passes one after the other, as the master composited before it kept codes: every tile
/// decoded to floats and scattered, every row filtered, then the frame added and averaged.
class Reference {
  public:
    Reference(int width, int height, const RenderSettings& s)
        : width_(width),
          height_(height),
          settings_(s),
          filter_{s.effectiveFilterX(), s.effectiveFilterY(), s.filterDepthThreshold,
                  s.filterNormalThreshold} {
        reset();
    }
    void reset() {
        accumulator_.reset(width_, height_, settings_.accumulate && settings_.progressiveFilter,
                           filter_.sizeX, filter_.sizeY);
    }
    FrameBuffer assemble(const std::vector<Tile>& tiles,
                         const std::vector<std::vector<std::uint8_t>>& wire) const {
        FrameBuffer f;
        f.reuse(width_, height_);
        for (std::size_t i = 0; i < tiles.size(); ++i) {
            proto::ByteReader in(wire[i], "TileResult");
            f.scatter(tiles[i], settings_.interleaveX, settings_.interleaveY,
                      proto::readTileChannels(in));
        }
        return f;
    }
    std::vector<glm::vec3> composite(const FrameBuffer& f) {
        const std::size_t pixels = std::size_t(width_) * height_;
        std::vector<glm::vec3> filtered(pixels), unfiltered(pixels), mean(pixels);
        discontinuityFilterRows(f, filter_, 0, height_, filtered);
        if (!settings_.accumulate) return filtered;
        compositeUnfilteredRows(f, 0, height_, unfiltered);
        accumulator_.addRows(filtered, unfiltered, 0, height_);
        accumulator_.endFrame();
        accumulator_.meanRows(mean, 0, height_);
        return mean;
    }

  private:
    int width_, height_;
    RenderSettings settings_;
    DiscontinuityFilterSettings filter_;
    Accumulator accumulator_;
};

struct Case {
    int width, height, n, m, tileSize;
    bool accumulate, progressive;
    unsigned threads;
};

std::string name(const Case& c) {
    return std::to_string(c.width) + "x" + std::to_string(c.height) + " interleave " +
           std::to_string(c.n) + "x" + std::to_string(c.m) + " accumulate " +
           std::to_string(c.accumulate) + " progressive " + std::to_string(c.progressive) +
           " threads " + std::to_string(c.threads);
}

// The compositor dequantizes, filters, accumulates and averages in one sweep over blocks of
// rows, on several threads, leaving the rows whose mean reads another block for a second
// sweep. What it shows must be the reference's, frame after frame, bit for bit: from the coded
// frame the master assembles and from a frame of floats, at heights that cut blocks anywhere,
// for every interleaving, with accumulation (and the progressive filter) on and off, across a
// reset of the accumulation and planes that come to life in a later frame.
TEST(FrameCompositor, OneSweepEqualsTheSeparatePassesBitForBit) {
    const Case cases[] = {
        {29, 5, 3, 3, 2, true, true, 3},   {29, 17, 3, 3, 2, true, true, 1},
        {29, 47, 3, 3, 4, true, true, 3},  {64, 70, 3, 3, 32, true, true, 2},
        {31, 33, 2, 4, 3, true, true, 3},  {23, 19, 1, 1, 8, true, true, 2},
        {40, 37, 3, 3, 4, true, false, 3}, {40, 21, 3, 3, 4, false, false, 2},
        {97, 50, 4, 4, 5, true, true, 4},
    };
    std::mt19937 rng(9);
    for (const Case& c : cases) {
        RenderSettings settings;
        settings.interleaveX = c.n, settings.interleaveY = c.m, settings.tileSize = c.tileSize;
        settings.accumulate = c.accumulate, settings.progressiveFilter = c.progressive;
        const auto tiles = makeTiles(c.width, c.height, c.n, c.m, c.tileSize);
        ThreadPool pool(c.threads);
        FrameCompositor coded(c.width, c.height, settings, pool);
        FrameCompositor floats(c.width, c.height, settings, pool);
        Reference reference(c.width, c.height, settings);
        proto::CodedFrame buffers[2];
        for (int frame = 0; frame < 7; ++frame) {
            if (frame == 4) {  // the view moved
                coded.resetAccumulation();
                floats.resetAccumulation();
                reference.reset();
            }
            proto::test::RandomTiles random;
            random.extremeScales = frame % 3 == 2;
            if (frame >= 2) random.planes |= kGlossy;
            const auto wire = random.encoded(tiles, c.n, c.m, rng);
            proto::CodedFrame& buffer = buffers[frame % 2];
            buffer.reuse(c.width, c.height, c.n, c.m, c.tileSize);
            for (std::size_t i = 0; i < tiles.size(); ++i) {
                proto::ByteReader in(wire[i], "TileResult");
                buffer.scatter(tiles[i], proto::readTileCodes(in));
            }
            const FrameBuffer f = reference.assemble(tiles, wire);
            const auto expected = reference.composite(f);
            for (FrameCompositor* compositor : {&coded, &floats}) {
                const Image& shown =
                    compositor == &coded ? compositor->composite(buffer) : compositor->composite(f);
                ASSERT_EQ(&shown, &compositor->shown());
                ASSERT_EQ(compositor->accumulatedFrames(), c.accumulate ? frame % 4 + 1 : 0);
                for (std::size_t p = 0; p < expected.size(); ++p)
                    ASSERT_EQ(std::memcmp(&shown.pixels[p], &expected[p], sizeof(glm::vec3)), 0)
                        << name(c) << (compositor == &coded ? " coded" : " floats") << " frame "
                        << frame << " pixel " << p << ": " << shown.pixels[p].x << " vs "
                        << expected[p].x;
            }
        }
    }
}

// Adaptive tiles: from the frame that leaves regions out, their pixels keep their mean, their
// estimate and their frame count (bit for bit where their whole neighbourhood is left out too),
// while pixels away from them (beyond the filter's and the pooled variance's reach) are exactly
// those of a compositor given every region. The left-out regions hold the cells of the last
// frame that rendered them, as the master fills them.
TEST(FrameCompositor, RegionsLeftOutKeepTheirPixelsAndCounts) {
    const int w = 48, h = 36, n = 3, m = 3, tileSize = 4;  // regions of 12 x 12: 4 x 3
    RenderSettings settings;
    settings.interleaveX = n, settings.interleaveY = m, settings.tileSize = tileSize;
    const auto tiles = makeTiles(w, h, n, m, tileSize);
    ThreadPool pool(3);
    FrameCompositor partial(w, h, settings, pool), full(w, h, settings, pool);
    TileRegions regions(w, h, n, m, tileSize);
    regions.setRendered(1, false);
    regions.setRendered(6, false);
    proto::CodedFrame buffer, kept;
    std::mt19937 rng(4);
    std::vector<glm::vec3> before;
    std::vector<float> errorBefore;
    for (int frame = 0; frame < 8; ++frame) {
        proto::test::RandomTiles random;
        const auto wire = random.encoded(tiles, n, m, rng);
        buffer.reuse(w, h, n, m, tileSize);
        for (std::size_t i = 0; i < tiles.size(); ++i) {
            proto::ByteReader in(wire[i], "TileResult");
            buffer.scatter(tiles[i], proto::readTileCodes(in));
        }
        full.composite(buffer);
        const bool leftOut = frame >= 4;
        if (frame == 3) {  // the last frame that renders them: its cells are kept
            kept.reuse(w, h, n, m, tileSize);
            for (int r = 0; r < regions.count(); ++r)
                if (!regions.rendered(r)) kept.copyRegion(buffer, regions.rectangle(r));
        }
        if (leftOut)
            for (int r = 0; r < regions.count(); ++r)
                if (!regions.rendered(r)) buffer.copyRegion(kept, regions.rectangle(r));
        const Image& shown = partial.composite(buffer, leftOut ? &regions : nullptr);
        if (frame == 3) {
            before = shown.pixels;
            errorBefore = partial.pixelRelMse();
        }
    }
    // The distance from pixel (x, y) to the nearest left-out pixel, in the max norm.
    const auto distance = [&](int x, int y) {
        int d = 1 << 20;
        for (int qy = 0; qy < h; ++qy)
            for (int qx = 0; qx < w; ++qx)
                if (!regions.rendered(regions.regionAt(qx, qy)))
                    d = std::min(d, std::max(std::abs(qx - x), std::abs(qy - y)));
        return d;
    };
    int inside = 0, away = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t p = std::size_t(y) * w + x;
            const bool left = !regions.rendered(regions.regionAt(x, y));
            EXPECT_EQ(partial.pixelFrames(x, y), left ? 4.0 : 8.0) << x << ", " << y;
            if (left) {
                // Inside: its own and its neighbours' sums are those of frame 3.
                bool deep = true;
                for (int dy = -2; dy <= 2; ++dy)
                    for (int dx = -2; dx <= 2; ++dx) {
                        const int qx = std::clamp(x + dx, 0, w - 1),
                                  qy = std::clamp(y + dy, 0, h - 1);
                        deep = deep && !regions.rendered(regions.regionAt(qx, qy));
                    }
                if (!deep) continue;
                ++inside;
                EXPECT_EQ(std::memcmp(&partial.shown().pixels[p], &before[p], sizeof(glm::vec3)), 0)
                    << x << ", " << y;
                EXPECT_EQ(partial.pixelRelMse()[p], errorBefore[p]) << x << ", " << y;
            } else if (distance(x, y) > 3) {
                ++away;
                EXPECT_EQ(std::memcmp(&partial.shown().pixels[p], &full.shown().pixels[p],
                                      sizeof(glm::vec3)),
                          0)
                    << x << ", " << y;
            }
        }
    EXPECT_GT(inside, 100);
    EXPECT_GT(away, 500);
    EXPECT_EQ(partial.accumulatedFrames(), 8);
}

}  // namespace
}  // namespace igi
