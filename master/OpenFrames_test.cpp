#include "OpenFrames.h"

#include <gtest/gtest.h>

namespace igi {
namespace {

ImageSettings image(int width, int height) {
    ImageSettings i;
    i.width = width;
    i.height = height;
    return i;
}

TEST(OpenFrames, BigImagesOpenFewerFramesButNeverFewerThanTwo) {
    const RenderSettings render;
    EXPECT_EQ(OpenFrames(image(640, 480), render).capacity(), 4u);
    EXPECT_EQ(OpenFrames(image(16384, 16384), render).capacity(), 2u);
}

TEST(OpenFrames, AFramesPlaceInTheAccumulationCountsFromItsEpochsFirstFrame) {
    RenderSettings render;
    OpenFrames frames(image(64, 48), render);
    EXPECT_EQ(frames.open(5, 0).accumulation, 0u);
    EXPECT_EQ(frames.open(6, 0).accumulation, 1u);
    EXPECT_EQ(frames.open(7, 1).accumulation, 0u);  // a new epoch starts the accumulation
    EXPECT_EQ(frames.open(8, 1).accumulation, 1u);
    EXPECT_EQ(frames.at(6).epoch, 0u);
    EXPECT_EQ(frames.at(7).epoch, 1u);

    render.accumulate = false;
    OpenFrames single(image(64, 48), render);
    single.open(0, 0);
    EXPECT_EQ(single.open(1, 0).accumulation, 0u);
}

TEST(OpenFrames, AFrameOpensWithABufferOfTheImageAndAClosedOnesRecordGoes) {
    OpenFrames frames(image(64, 48), RenderSettings{});
    EXPECT_EQ(frames.open(0, 0).buffer.width(), 64);
    frames.at(0).decoding = 3;
    frames.close(0);
    EXPECT_THROW(frames.at(0), std::out_of_range);
    // The next frame gets the kept buffer, laid out anew, in a fresh record.
    const OpenFrames::Frame& next = frames.open(1, 0);
    EXPECT_EQ(next.buffer.width(), 64);
    EXPECT_EQ(next.buffer.height(), 48);
    EXPECT_EQ(next.decoding, 0);
    EXPECT_EQ(next.accumulation, 1u);
}

TEST(OpenFrames, AnAssignmentCarriesTheTileAndItsFramesPlaceInTheAccumulation) {
    OpenFrames frames(image(64, 48), RenderSettings{});
    frames.open(3, 0);
    frames.open(4, 0);
    const Tile tile{6, 9, 12, 15, 1, 2};
    const proto::TileAssign a = frames.assignment(4, 17, tile);
    EXPECT_EQ(a.tileId, 17u);
    EXPECT_EQ(a.x0, 6);
    EXPECT_EQ(a.y0, 9);
    EXPECT_EQ(a.width, 12);
    EXPECT_EQ(a.height, 15);
    EXPECT_EQ(a.kx, 1);
    EXPECT_EQ(a.ky, 2);
    EXPECT_EQ(a.accumulation, 1u);
}

}  // namespace
}  // namespace igi
