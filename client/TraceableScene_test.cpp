#include "TraceableScene.h"

#include <random>

#include <gtest/gtest.h>

#include "EmbreeDevice.h"
#include "SceneGeometry.h"
#include "TestScenes.h"

namespace igi {
namespace {

// Packets must answer exactly as single rays do: the integrator uses both, and an image must
// not depend on which one a shadow ray went through.
TEST(TraceableScene, PacketsOfShadowRaysAnswerAsSingleRaysDo) {
    const Scene scene = testing::cornellBox(1.0f, true);
    EmbreeDevice device;
    SceneGeometry geometry(device, scene);
    TraceableScene traceable(geometry);

    std::mt19937 random(7);
    // Origins inside the unit box; targets inside or beyond its walls, so that the walls, the
    // block and the glass ball all stand in the way of some rays.
    std::uniform_real_distribution<float> inside(0.05f, 0.95f), around(-0.3f, 1.3f),
        unit(0.0f, 1.0f);
    RayCounters single, packed;
    int blockedCount = 0, freeCount = 0;
    for (int round = 0; round < 2000; ++round) {
        const glm::vec3 origin(inside(random), inside(random), inside(random));
        const int count = 1 + round % TraceableScene::kPacket;  // partial packets too
        glm::vec3 directions[TraceableScene::kPacket];
        float tfar[TraceableScene::kPacket];
        for (int i = 0; i < count; ++i) {
            const glm::vec3 target(around(random), around(random), around(random));
            directions[i] = glm::normalize(target - origin);
            tfar[i] = glm::length(target - origin) * (0.2f + 0.8f * unit(random));
        }
        bool blocked[TraceableScene::kPacket];
        traceable.occluded8(origin, directions, tfar, count, blocked, packed);
        for (int i = 0; i < count; ++i) {
            const bool expected = traceable.occluded(origin, directions[i], tfar[i], single);
            ASSERT_EQ(blocked[i], expected) << "round " << round << ", ray " << i;
            (expected ? blockedCount : freeCount)++;
        }
    }
    // Both outcomes occur often, or the comparison proves little.
    EXPECT_GT(blockedCount, 500);
    EXPECT_GT(freeCount, 500);
    EXPECT_EQ(packed.shadowRays, single.shadowRays);
    EXPECT_EQ(packed.rays, single.rays);
}

}  // namespace
}  // namespace igi
