#include "TileScheduler.h"

#include <map>
#include <set>
#include <thread>

#include <gtest/gtest.h>

namespace igi {
namespace {

std::vector<Tile> layout() {
    return makeTiles(96, 96, 3, 3, 16);
}  // 4 regions x 9 cells = 36 tiles

TEST(TileScheduler, EveryTileOfAFrameIsHandedOutOnceThenTheFrameCompletes) {
    TileScheduler s(layout(), 9);
    s.openFrame(0);
    std::set<std::uint32_t> given;
    while (auto a = s.next(1)) {
        ASSERT_FALSE(a->duplicate);
        EXPECT_TRUE(given.insert(a->tile).second);
        if (given.size() == layout().size()) break;
    }
    EXPECT_EQ(given.size(), layout().size());
    EXPECT_TRUE(s.frameFullyAssigned(0));
    EXPECT_FALSE(s.frameDone(0));
    for (auto t : given) EXPECT_TRUE(s.complete(1, 0, t));
    EXPECT_TRUE(s.frameDone(0));
    EXPECT_FALSE(s.complete(1, 0, *given.begin()));  // a second result for a done tile is dropped
}

// A client that joined while frames 0 and 1 were open (of epochs it may not have) gets no tile
// of them, not even a late copy, and goes on to frame 2.
TEST(TileScheduler, AClientGetsNoTileOfAFrameBeforeItsFirst) {
    TileScheduler s(layout(), 9);
    s.openFrame(0);
    s.openFrame(1);
    ASSERT_TRUE(s.next(1));  // client 1 holds a tile of frame 0, late by any measure below
    EXPECT_FALSE(s.next(2, 0.0, 2)) << "frames 0 and 1 are before client 2's first";
    s.openFrame(2);
    const auto a = s.next(2, 0.0, 2);
    ASSERT_TRUE(a);
    EXPECT_EQ(a->frame, 2u);
    // Without the bound the same client would have taken frame 0's pending tiles first.
    const auto b = s.next(3, 0.0);
    ASSERT_TRUE(b);
    EXPECT_EQ(b->frame, 0u);
}

TEST(TileScheduler, ClientsStayOnTheirSetAndSpreadOverDifferentSets) {
    const auto tiles = layout();
    TileScheduler s(tiles, 9);
    s.openFrame(0);
    std::map<ClientId, std::set<int>> sets;
    for (int round = 0; round < 12; ++round)
        for (ClientId c : {1u, 2u, 3u}) {
            auto a = s.next(c);
            ASSERT_TRUE(a);
            sets[c].insert(tiles[a->tile].setIndex(3));
            s.complete(c, 0, a->tile);
        }
    // 36 tiles, 3 clients: each client needs 3 sets (4 tiles per set), and no two share one.
    std::set<int> all;
    for (auto& [c, ks] : sets) {
        EXPECT_EQ(ks.size(), 3u) << "client " << c;
        all.insert(ks.begin(), ks.end());
    }
    EXPECT_EQ(all.size(), 9u);
}

TEST(TileScheduler, ALeavingClientsTilesGoToOthers) {
    TileScheduler s(layout(), 9);
    s.openFrame(0);
    std::vector<std::uint32_t> heldBy1;
    for (int i = 0; i < 5; ++i) heldBy1.push_back(s.next(1)->tile);
    EXPECT_EQ(s.inFlight(1), 5);
    EXPECT_EQ(s.releaseClient(1), 5);
    EXPECT_EQ(s.inFlight(1), 0);
    std::set<std::uint32_t> given;
    while (auto a = s.next(2)) {
        given.insert(a->tile);
        s.complete(2, 0, a->tile);
        if (s.frameDone(0)) break;
    }
    for (auto t : heldBy1) EXPECT_TRUE(given.count(t));
    EXPECT_TRUE(s.frameDone(0));
    EXPECT_FALSE(s.complete(1, 0, heldBy1[0]));  // the departed client's late result is dropped
}

TEST(TileScheduler, OnlyAHolderCanCompleteATile) {
    TileScheduler s(layout(), 9);
    s.openFrame(0);
    const auto a = s.next(1);
    EXPECT_FALSE(s.complete(2, 0, a->tile));  // never given to client 2
    EXPECT_FALSE(s.complete(1, 0, 9999));     // no such tile
    EXPECT_FALSE(s.complete(1, 7, a->tile));  // no such frame
    EXPECT_TRUE(s.complete(1, 0, a->tile));
}

TEST(TileScheduler, IdleClientsGetCopiesOfOldTilesFirstResultWins) {
    TileScheduler s(makeTiles(6, 3, 3, 3, 1), 9);  // 2 regions x 9 cells = 18 tiles
    s.openFrame(0);
    // The slow client's first tile comes back at once: its latency is measured (about zero).
    s.complete(1, 0, s.next(1)->tile);
    ASSERT_TRUE(s.latency(1).has_value());
    std::vector<std::uint32_t> slow;
    while (auto a = s.next(1)) slow.push_back(a->tile);  // then it holds everything else
    ASSERT_EQ(slow.size(), 17u);
    EXPECT_FALSE(s.next(2, 10.0));  // too young to copy
    const auto copy = s.next(2, 0.0);
    ASSERT_TRUE(copy);
    EXPECT_TRUE(copy->duplicate);
    EXPECT_EQ(copy->tile, slow[0]);              // the oldest work first
    EXPECT_TRUE(s.complete(2, 0, copy->tile));   // the copy's result wins
    EXPECT_FALSE(s.complete(1, 0, copy->tile));  // the original's is dropped
    EXPECT_EQ(s.inFlight(1), 16);
}

TEST(TileScheduler, ATileOfAClientNotYetMeasuredIsNotCopiedAtOnce) {
    // A client that just joined builds its light sets first; racing it at once would leave it
    // nothing but lost copies.
    TileScheduler s(makeTiles(3, 3, 3, 3, 1), 9);
    s.openFrame(0);
    while (s.next(1)) {
    }
    EXPECT_FALSE(s.latency(1).has_value());
    EXPECT_FALSE(s.next(2, 0.0));
}

TEST(TileScheduler, PipelinedFramesTheOldestFirst) {
    TileScheduler s(makeTiles(3, 3, 3, 3, 1), 9);  // 9 tiles of one pixel
    s.openFrame(0);
    for (int i = 0; i < 9; ++i) EXPECT_EQ(s.next(1)->frame, 0u);
    s.openFrame(1);
    const auto a = s.next(1);
    EXPECT_EQ(a->frame, 1u);
    EXPECT_EQ(s.releaseClient(1), 10);
    EXPECT_EQ(s.next(2)->frame, 0u);  // released tiles of frame 0 come before frame 1's
    EXPECT_THROW(s.openFrame(1), std::logic_error);
}

}  // namespace
}  // namespace igi

namespace igi {
namespace {

TEST(TileScheduler, AReopenedTileIsHandedOutAgainAndTheFrameWaitsForIt) {
    TileScheduler s(makeTiles(3, 3, 3, 3, 1), 9);
    s.openFrame(0);
    std::vector<std::uint32_t> tiles;
    while (auto a = s.next(1)) tiles.push_back(a->tile);
    for (auto t : tiles) s.complete(1, 0, t);
    ASSERT_TRUE(s.frameDone(0));
    s.reopen(0, tiles[3]);
    EXPECT_FALSE(s.frameDone(0));
    const auto again = s.next(2);
    ASSERT_TRUE(again);
    EXPECT_EQ(again->tile, tiles[3]);
    EXPECT_FALSE(again->duplicate);
    EXPECT_TRUE(s.complete(2, 0, tiles[3]));
    EXPECT_TRUE(s.frameDone(0));
}

// Adaptive tiles: the tiles a frame leaves out are never handed out, not even as late copies,
// and the frame completes with the others; a result for one is dropped.
TEST(TileScheduler, TilesLeftOutAreNeverHandedOut) {
    TileScheduler s(layout(), 9);
    std::vector<bool> leftOut(layout().size(), false);
    for (std::size_t i = 0; i < leftOut.size(); i += 3) leftOut[i] = true;
    s.openFrame(0, &leftOut);
    std::set<std::uint32_t> given;
    while (auto a = s.next(1)) {
        if (a->duplicate) break;
        EXPECT_FALSE(leftOut[a->tile]) << a->tile;
        EXPECT_TRUE(given.insert(a->tile).second);
    }
    EXPECT_EQ(given.size(), 24u);
    EXPECT_TRUE(s.frameFullyAssigned(0));
    for (std::uint32_t t = 0; t < 36; ++t) {
        if (leftOut[t]) {
            EXPECT_FALSE(s.complete(1, 0, t)) << "tile " << t << " was never given";
        }
    }
    EXPECT_FALSE(s.frameDone(0));
    for (auto t : given) EXPECT_TRUE(s.complete(1, 0, t));
    EXPECT_TRUE(s.frameDone(0));
    std::vector<bool> wrong(5, true);
    EXPECT_THROW(s.openFrame(1, &wrong), std::logic_error);
}

}  // namespace
}  // namespace igi
