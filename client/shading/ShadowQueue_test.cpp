#include "shading/ShadowQueue.h"

#include <cstring>
#include <random>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "testing/TestScenes.h"
#include "tracing/EmbreeDevice.h"
#include "tracing/SceneGeometry.h"

namespace igi {
namespace {

bool sameBits(glm::vec3 a, glm::vec3 b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

struct Connection {
    std::uint32_t target;
    glm::vec3 direction;
    float tfar;
    glm::vec3 irradiance, glossy;
};

// Many points' rays, to targets they share (in any order, with gaps in the numbering) and to
// targets of their own, traced together in packets by target: each point's sums are those of
// its rays traced one at a time and added in the order queued, bit for bit. Twice through one
// queue, the second time with fewer targets than the first, as a thread's queue is reused.
// Points queue their rays one at a time (add) or in one run (addEach), alternately.
TEST(ShadowQueue, PointsTracedTogetherSumAsEachPointsRaysTracedAlone) {
    const Scene scene = testing::cornellBox(1.0f, true);
    EmbreeDevice device;
    SceneGeometry geometry(device, scene);
    TraceableScene traceable(geometry);
    std::mt19937 random(5);
    std::uniform_real_distribution<float> inside(0.05f, 0.95f), around(-0.3f, 1.3f), unit(0, 1);
    ShadowQueue queue;
    int blocked = 0, free = 0;
    for (const int width : {16, 8}) {
        traceable.setPacketWidth(width);
        for (const std::uint32_t targets : {40u, 7u}) {
            std::vector<glm::vec3> shared(targets);
            for (glm::vec3& t : shared) t = {around(random), around(random), around(random)};
            std::vector<glm::vec3> origins;
            std::vector<std::vector<Connection>> connections;
            queue.clear();
            for (int p = 0; p < 70; ++p) {
                const glm::vec3 origin(inside(random), inside(random), inside(random));
                origins.push_back(origin);
                connections.emplace_back();
                EXPECT_EQ(queue.beginPoint(origin), std::uint32_t(p));
                // 11 to 13 rays a point: packets end anywhere, not only on a multiple of four.
                for (int k = 0; k < 11 + p % 3; ++k) {
                    const bool own = k % 4 == 3;
                    const std::uint32_t t =
                        own ? ShadowQueue::kOwnTarget : std::uint32_t(random() % targets) / 2 * 2;
                    const glm::vec3 end =
                        own ? glm::vec3(around(random), around(random), around(random)) : shared[t];
                    const Connection c{t, glm::normalize(end - origin),
                                       glm::length(end - origin) * 0.999f,
                                       glm::vec3(unit(random), unit(random), 1e-3f * unit(random)),
                                       glm::vec3(unit(random) * 1e5f, 0.0f, unit(random))};
                    // Every other point queues its rays in one run (addEach), the rest one by one.
                    if (p % 2 == 0)
                        queue.add(c.target, c.direction, c.tfar, c.irradiance, c.glossy);
                    connections.back().push_back(c);
                }
                const std::vector<Connection>& mine = connections.back();
                if (p % 2 == 1)
                    queue.addEach(mine.size(), [&](std::size_t k) {
                        const Connection& c = mine[k];
                        return ShadowQueue::Connection{c.target, c.direction, c.tfar, c.irradiance,
                                                       c.glossy};
                    });
            }
            RayCounters together, alone;
            queue.trace(traceable, together);
            ASSERT_EQ(queue.points(), origins.size());
            for (std::size_t p = 0; p < origins.size(); ++p) {
                glm::vec3 e(0.0f), g(0.0f), qe, qg;
                for (const Connection& c : connections[p]) {
                    const bool b = traceable.occluded(origins[p], c.direction, c.tfar, alone);
                    (b ? blocked : free)++;
                    if (b) continue;
                    e += c.irradiance;
                    g += c.glossy;
                }
                queue.sum(std::uint32_t(p), qe, qg);
                ASSERT_TRUE(sameBits(qe, e) && sameBits(qg, g))
                    << "point " << p << ", width " << width << ", " << targets << " targets";
            }
            EXPECT_EQ(together.shadowRays, alone.shadowRays);
        }
    }
    // Both outcomes are common, or the sums prove little.
    EXPECT_GT(blocked, 500);
    EXPECT_GT(free, 500);
}

}  // namespace
}  // namespace igi
