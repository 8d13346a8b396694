#include "SceneTimeline.h"

#include <gtest/gtest.h>

#include "Messages.h"

namespace igi {
namespace {

SceneState twoObjects() {
    SceneState s;
    s.transforms.resize(2);
    return s;
}

// A frame begun and finished before the next begins.
void render(SceneTimeline& timeline, std::uint32_t frame) {
    timeline.beginFrame(frame);
    timeline.endFrame(frame);
}

std::vector<SceneChange> moveTo(std::uint32_t mesh, float x) {
    Transform t;
    t.translate.x = x;
    return {TransformChange{mesh, t}};
}

// A client that joins after the sky was changed gets that sky with the rest of the state.
TEST(SceneTimeline, AJoinerGetsTheChangedEnvironment) {
    SceneState loaded = twoObjects();
    loaded.environment.texture = 0;
    loaded.environment.radiance = glm::vec3(1.0f);
    SceneTimeline timeline(loaded, nullptr);
    render(timeline, 0);
    Environment brighter = loaded.environment;
    brighter.radiance = glm::vec3(4.0f);
    brighter.rotateDeg = 15.0f;
    timeline.control({EnvironmentChange{brighter}});
    render(timeline, 1);
    SceneState joined = loaded;
    applyChanges(joined, timeline.join().changes);
    EXPECT_EQ(joined.environment, brighter);
    EXPECT_EQ(joined, timeline.state());
}

// New settings start the lighting afresh on every client (as a session started with them
// would): a joiner needs nothing from before them, whatever the depth; with the settings in
// force, from the base on.
TEST(SceneTimeline, ASettingsChangeIsTheBaseOfEveryLaterJoin) {
    SceneState loaded = twoObjects();
    loaded.render.gi = GiMode::Spt;
    SceneTimeline timeline(loaded, nullptr, proto::kMaxHistoryEpochs);
    render(timeline, 0);
    timeline.control(moveTo(0, 1.0f));
    render(timeline, 1);  // epoch 1
    EXPECT_EQ(timeline.join().history.size(), 1u);
    RenderSettings more = loaded.render;
    more.sptBudget = 12;
    timeline.control({SettingsChange{more}});
    render(timeline, 2);  // epoch 2: the new settings
    timeline.control(moveTo(1, 2.0f));
    render(timeline, 3);  // epoch 3 continues epoch 2's lighting
    ASSERT_EQ(timeline.epoch(), 3u);
    const SceneTimeline::Join join = timeline.join();
    EXPECT_EQ(join.baseFirstFrame, 2u);
    ASSERT_EQ(join.history.size(), 1u);
    EXPECT_EQ(join.history[0].firstFrame, 3u);
    EXPECT_TRUE(timeline.historyComplete());
    SceneState state = loaded;
    applyChanges(state, join.changes);
    EXPECT_EQ(state.render, more);
    EXPECT_EQ(state.transforms[0].translate.x, 1.0f);
    applyChanges(state, join.history[0].changes);
    EXPECT_EQ(state, timeline.state());
}

// A session started at frame F (--first-frame) begins its epoch 0 there.
TEST(SceneTimeline, TheFirstEpochBeginsAtTheSessionsFirstFrame) {
    SceneTimeline timeline(twoObjects(), nullptr, 8, 40);
    render(timeline, 40);
    EXPECT_EQ(timeline.join().baseFirstFrame, 40u);
}

// A joiner gets the state of the base epoch and the epochs after it, at most the depth: applying
// them in order gives the current state, and the frames are those the epochs began at.
TEST(SceneTimeline, AJoinerGetsTheLatestEpochsAndTheStateBeforeThem) {
    SceneTimeline timeline(twoObjects(), nullptr, 2);
    std::uint32_t frame = 0;
    render(timeline, frame++);  // epoch 0
    for (int epoch = 1; epoch <= 4; ++epoch) {
        timeline.control(moveTo(std::uint32_t(epoch % 2), float(epoch)));
        render(timeline, frame++);  // frames 1, 3, 5, 7 begin epochs 1 .. 4
        render(timeline, frame++);  // and the scene holds for one more frame
    }
    ASSERT_EQ(timeline.epoch(), 4u);
    const SceneTimeline::Join join = timeline.join();
    ASSERT_EQ(join.history.size(), 2u);
    EXPECT_EQ(join.baseFirstFrame, 3u) << "epoch 2 began at frame 3";
    EXPECT_EQ(join.history[0].firstFrame, 5u);
    EXPECT_EQ(join.history[1].firstFrame, 7u);
    SceneState state = twoObjects();
    applyChanges(state, join.changes);
    EXPECT_EQ(state.transforms[0].translate.x, 2.0f) << "the base: epoch 2";
    EXPECT_EQ(state.transforms[1].translate.x, 1.0f);
    for (const auto& e : join.history) applyChanges(state, e.changes);
    EXPECT_EQ(state, timeline.state());
    EXPECT_FALSE(timeline.historyComplete());
}

TEST(SceneTimeline, WithoutDepthAJoinerStartsInTheCurrentState) {
    SceneTimeline timeline(twoObjects(), nullptr);
    render(timeline, 0);
    timeline.control(moveTo(1, 3.0f));
    render(timeline, 1);
    const SceneTimeline::Join join = timeline.join();
    EXPECT_TRUE(join.history.empty());
    EXPECT_EQ(join.baseFirstFrame, 1u);
    SceneState state = twoObjects();
    applyChanges(state, join.changes);
    EXPECT_EQ(state, timeline.state());
}

TEST(SceneTimeline, AHistoryDeepEnoughReachesTheLoadedScene) {
    SceneTimeline timeline(twoObjects(), nullptr, 8);
    render(timeline, 0);
    timeline.control(moveTo(0, 1.0f));
    render(timeline, 1);
    const SceneTimeline::Join join = timeline.join();
    EXPECT_TRUE(timeline.historyComplete());
    EXPECT_TRUE(join.changes.empty());
    EXPECT_EQ(join.baseFirstFrame, 0u);
    ASSERT_EQ(join.history.size(), 1u);
    EXPECT_EQ(join.history[0].firstFrame, 1u);
}

// A joiner may get any tile of a frame still open when the client holding it leaves: it gets
// every epoch of the open frames, past the depth its GI mode needs, until they are finished.
TEST(SceneTimeline, AJoinerGetsTheEpochsOfTheFramesStillOpen) {
    SceneTimeline timeline(twoObjects(), nullptr);
    render(timeline, 0);
    timeline.control(moveTo(0, 1.0f));
    timeline.beginFrame(1);  // epoch 1, open
    timeline.control(moveTo(0, 2.0f));
    timeline.beginFrame(2);  // epoch 2, open
    timeline.control(moveTo(0, 3.0f));
    timeline.beginFrame(3);  // epoch 3, open
    ASSERT_EQ(timeline.epoch(), 3u);
    SceneTimeline::Join join = timeline.join();
    EXPECT_EQ(timeline.baseEpoch(), 1u);
    EXPECT_EQ(join.baseFirstFrame, 1u);
    ASSERT_EQ(join.history.size(), 2u);
    EXPECT_EQ(join.history[0].firstFrame, 2u);
    EXPECT_EQ(join.history[1].firstFrame, 3u);
    SceneState state = twoObjects();
    applyChanges(state, join.changes);
    EXPECT_EQ(state.transforms[0].translate.x, 1.0f) << "the base: frame 1's epoch";
    for (const auto& e : join.history) applyChanges(state, e.changes);
    EXPECT_EQ(state, timeline.state());

    // Once they are finished, without depth, a joiner starts in the current state again.
    timeline.endFrame(1);
    EXPECT_EQ(timeline.baseEpoch(), 2u);
    EXPECT_EQ(timeline.join().history.size(), 1u);
    timeline.endFrame(2);
    timeline.endFrame(3);
    join = timeline.join();
    EXPECT_EQ(timeline.baseEpoch(), 3u);
    EXPECT_TRUE(join.history.empty());
    state = twoObjects();
    applyChanges(state, join.changes);
    EXPECT_EQ(state, timeline.state());
}

// New settings bound what a joiner needs, but not below a frame still open.
TEST(SceneTimeline, AFrameOpenBeforeNewSettingsKeepsItsEpochForJoiners) {
    SceneState loaded = twoObjects();
    SceneTimeline timeline(loaded, nullptr);
    render(timeline, 0);
    timeline.control(moveTo(0, 1.0f));
    timeline.beginFrame(1);  // epoch 1, open
    RenderSettings more = loaded.render;
    more.vplPaths = 64;
    timeline.control({SettingsChange{more}});
    timeline.beginFrame(2);  // epoch 2: the new settings
    EXPECT_EQ(timeline.baseEpoch(), 1u);
    EXPECT_TRUE(timeline.historyComplete()) << "the settings epoch is in the history";
    timeline.endFrame(1);
    EXPECT_EQ(timeline.baseEpoch(), 2u);
    EXPECT_TRUE(timeline.historyComplete());
    EXPECT_EQ(timeline.join().baseFirstFrame, 2u);
}

// Joiners replay exactly the history their mode's lighting depends on: a stream window's
// worth for photon streaming, everything kept for SPT and photon mapping, nothing for the
// stateless modes or the path tracer.
TEST(JoinHistoryDepth, FollowsTheGiMode) {
    RenderSettings s;
    s.gi = GiMode::Igi;
    EXPECT_EQ(joinHistoryDepth(s), 0u);
    s.gi = GiMode::Cache;
    EXPECT_EQ(joinHistoryDepth(s), 0u);
    s.gi = GiMode::Stream;
    s.streamWindow = 5;
    EXPECT_EQ(joinHistoryDepth(s), 4u);
    s.streamWindow = 0;
    EXPECT_EQ(joinHistoryDepth(s), 0u);
    s.gi = GiMode::Spt;
    EXPECT_EQ(joinHistoryDepth(s), proto::kMaxHistoryEpochs);
    s.gi = GiMode::PhotonMap;
    EXPECT_EQ(joinHistoryDepth(s), proto::kMaxHistoryEpochs);
    s.integrator = IntegratorKind::Path;
    EXPECT_EQ(joinHistoryDepth(s), 0u);
}

}  // namespace
}  // namespace igi
