#include "modes/stream/PhotonStream.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "lights/SurfaceLights.h"
#include "modes/stream/StreamLighting.h"
#include "sampling/LightPathSampler.h"
#include "testing/TestScenes.h"

namespace igi {
namespace {

using testing::InProcessRenderer;

constexpr std::uint32_t kBox = 5;  // cornellBox's mesh index of the turned box

Scene streamingBox() {
    Scene s = testing::cornellBox(1.0f);
    s.render.gi = GiMode::Stream;
    s.render.streamVsls = 64;
    s.render.streamPhotons = 512;
    s.render.streamWindow = 4;
    return s;
}

TEST(SurfaceLights, PlacementIsAFunctionOfTheSceneAndTheSeedOnly) {
    const Scene s = streamingBox();
    const SceneState state = SceneState::of(s);
    const auto a = placeSurfaceLights(s, state, 64, 1), b = placeSurfaceLights(s, state, 64, 1);
    EXPECT_EQ(a, b);
    EXPECT_EQ(a.size(), 64u);
    EXPECT_NE(a, placeSurfaceLights(s, state, 64, 2));
    bool onBox = false;
    for (const SurfaceLightSite& site : a) {
        const Material& m = s.materials[s.meshes[site.mesh].materialIds[site.triangle]];
        EXPECT_FALSE(m.isEmissive() || m.isSpecular());
        EXPECT_GT(site.b1, 0.0f);  // inside the shrunk triangle: off its edges
        EXPECT_GT(site.b2, 0.0f);
        EXPECT_LT(site.b1 + site.b2, 1.0f);
        onBox = onBox || site.mesh == kBox;
    }
    EXPECT_TRUE(onBox);
}

// The paper's Algorithm 1 removes a point of the closest pair, again and again.
TEST(SurfaceLights, ThinningRemovesThePointsClosestToANeighbour) {
    const std::vector<glm::vec3> p = {{0, 0, 0}, {1, 0, 0},    {1.1f, 0, 0},
                                      {3, 0, 0}, {3.5f, 0, 0}, {6, 0, 0}};
    const std::vector<bool> four = thinSurfaceLights(p, 4);
    EXPECT_EQ(std::count(four.begin(), four.end(), true), 4);
    EXPECT_NE(four[1], four[2]) << "one of the closest pair (1, 1.1) goes";
    EXPECT_NE(four[3], four[4]) << "then one of the next (3, 3.5)";
    EXPECT_TRUE(four[0] && four[5]);
    EXPECT_EQ(thinSurfaceLights(p, 6), std::vector<bool>(6, true));
}

TEST(SurfaceLights, AMovedObjectsLightsMoveWithIt) {
    const Scene s = streamingBox();
    const SceneState still = SceneState::of(s);
    const auto sites = placeSurfaceLights(s, still, 64, 1);
    SceneState moved = still;
    const glm::vec3 delta(0.1f, 0.0f, -0.05f);
    moved.transforms[kBox].translate += delta;
    const auto before = surfaceLightsIn(s, still, sites), after = surfaceLightsIn(s, moved, sites);
    for (std::size_t i = 0; i < sites.size(); ++i) {
        if (sites[i].mesh == kBox) {
            EXPECT_NEAR(glm::distance(after[i].position, before[i].position + delta), 0.0f, 1e-5f);
            EXPECT_NEAR(glm::dot(after[i].normal, before[i].normal), 1.0f, 1e-5f);
        } else {
            EXPECT_EQ(after[i].position, before[i].position);
        }
    }
}

TEST(PhotonStream, DepositsKeepEveryPhotonsPower) {
    const Scene s = streamingBox();
    InProcessRenderer r(s);
    const LightingSetBuilder& builder = r.renderer().builder();
    const SceneState state = SceneState::of(s);
    const auto lights = surfaceLightsIn(s, state, placeSurfaceLights(s, state, 64, 1));
    RayCounters rays;
    const PhotonBatch batch = shootPhotonBatch(builder, lights, 1, 100, 512, rays);
    const LightPathSampler sampler(1, 100, SampleStream::PhotonStream, 0, 512,
                                   std::uint32_t(builder.maxLightPathLength(true)));
    glm::dvec3 expected(0.0);
    int impacts = 0;
    builder.traceLightPaths(sampler, LightingSetBuilder::PathEnd::Roulette, true, rays,
                            [&](const Vpl& v) {
                                expected += glm::dvec3(v.power) * 512.0;
                                ++impacts;
                            });
    glm::dvec3 deposited(0.0);
    for (std::size_t i = 0; i < lights.size(); ++i)
        deposited += glm::dvec3(batch.front[i]) + glm::dvec3(batch.back[i]);
    EXPECT_GT(impacts, 512);  // most paths bounce more than once in a closed box
    for (int c = 0; c < 3; ++c) {
        EXPECT_GT(expected[c], 0.0);
        EXPECT_NEAR(deposited[c] / expected[c], 1.0, 1e-4);
    }
}

std::shared_ptr<const std::vector<SurfaceLightSite>> twoSites() {
    return std::make_shared<const std::vector<SurfaceLightSite>>(2);
}

PhotonBatch batchOf(float value) {
    PhotonBatch b;
    b.front = {glm::vec3(value), glm::vec3(0.0f)};
    b.back = {glm::vec3(0.0f), glm::vec3(2.0f * value)};
    b.paths = 1;
    return b;
}

TEST(PhotonStream, ThePoolHoldsTheLastWindowOfBatchesOldestOut) {
    const auto first = PhotonStream::first(
        twoSites(), 5, 40, 3, [](std::uint32_t index) { return batchOf(float(index)); });
    EXPECT_EQ(first->epoch(), 5u);
    const float b = float(PhotonStream::batchIndex(40));  // keyed by the frame, not the epoch
    std::vector<glm::vec3> front, back;
    first->power(front, back);
    EXPECT_EQ(first->batches(), 3u);
    EXPECT_FLOAT_EQ(front[0].x, (b - 2 + b - 1 + b) / 3.0f);
    EXPECT_FLOAT_EQ(back[1].x, 2.0f * (b - 2 + b - 1 + b) / 3.0f);
    const auto second = first->next(6, 3, std::make_shared<const PhotonBatch>(batchOf(1000.0f)));
    second->power(front, back);
    EXPECT_EQ(second->batches(), 3u);
    EXPECT_FLOAT_EQ(front[0].x, (b - 1 + b + 1000.0f) / 3.0f);
    EXPECT_EQ(second->epoch(), 6u);
    // The first epoch's pool is untouched: tiles of that epoch keep theirs.
    first->power(front, back);
    EXPECT_FLOAT_EQ(front[0].x, (b - 2 + b - 1 + b) / 3.0f);
}

TEST(StreamLighting, TheFirstFrameIsLitByTheVslsAndAccumulatedFramesByIgi) {
    InProcessRenderer r(streamingBox());
    const auto* stream = dynamic_cast<const StreamLighting*>(&r.renderer().method());
    ASSERT_NE(stream, nullptr);
    const float offset = 1e-3f;  // the VPL sits just off its VSL's surface
    std::size_t vsls = 0;
    const int sets = streamingBox().render.setCount();
    for (std::uint32_t k = 0; k < std::uint32_t(sets); ++k) {
        const LightingSet first = stream->build(0, 0, k);
        for (const Vpl& v : first.indirect) {
            bool atVsl = false;
            for (const SurfaceLight& l : stream->lights())
                atVsl = atVsl || glm::distance(l.position, v.position) < offset;
            EXPECT_TRUE(atVsl);
        }
        vsls += first.indirect.size();
        const LightingSet later = stream->build(1, 1, k),
                          igi = r.renderer().builder().build(1, 1, k);
        ASSERT_EQ(later.indirect.size(), igi.indirect.size());
        for (std::size_t i = 0; i < igi.indirect.size(); ++i)
            EXPECT_EQ(later.indirect[i].position, igi.indirect[i].position);
    }
    EXPECT_GE(vsls, 48u);  // nearly every VSL lit, each in exactly one set
}

}  // namespace
}  // namespace igi
