#include "modes/cache/IrradianceCache.h"

#include <cstring>
#include <memory>
#include <thread>

#include <gtest/gtest.h>

#include "SceneVersion.h"
#include "modes/cache/CacheLighting.h"
#include "testing/TestEpochs.h"
#include "testing/TestScenes.h"
#include "tracing/EmbreeDevice.h"
#include "tracing/SceneGeometry.h"

namespace igi {
namespace {

constexpr std::uint32_t kBox = 5;  // cornellBox's turned box

Scene cacheBox() {
    Scene s = testing::cornellBox(1.0f);
    s.render.gi = GiMode::Cache;
    s.render.cacheSpacing = 0.05f;
    return s;
}

using Epochs = testing::Epochs<CacheLighting>;

bool sameBits(glm::vec3 a, glm::vec3 b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

std::uint32_t recordCount(const IrradianceCache& c) {
    return std::uint32_t(2 * c.sites()->sites.size());
}

void computeAll(const IrradianceCache& c) {
    RayCounters rays;
    for (std::uint32_t r = 0; r < recordCount(c); ++r) c.record(r, rays);
}

// Records brought up to date after a change (the paper's Algorithm 1) are the records a
// client that never saw the earlier state computes: bit for bit, for a moved object (cases
// 3-5), a moved light (every VPL changes: cases 1 and 2) and a camera move (nothing to do).
TEST(IrradianceCache, AnUpdatedRecordEqualsOneComputedAnew) {
    Epochs client(cacheBox());
    Epochs joiner(cacheBox());
    SceneState state = SceneState::of(client.scene());
    computeAll(*client.begin(state).stable());

    SceneState moved = state;
    moved.transforms[kBox].translate = {-0.25f, 0.0f, 0.1f};
    moved.transforms[kBox].rotateDeg = {0.0f, 15.0f, 0.0f};
    SceneState light = moved;
    light.quadLights[0].corner.x += 0.1f;
    SceneState camera = light;
    camera.camera.position.x += 0.2f;

    for (const SceneState* s : {&moved, &light, &camera}) {
        const auto& updated = *client.begin(*s).stable();
        const auto& fresh = *joiner.begin(*s, 0, true).stable();
        const std::uint64_t tracedBefore = updated.recordsTraced();
        const std::uint64_t updatedBefore = updated.recordsUpdated();
        RayCounters rays;
        std::uint32_t differ = 0, lit = 0;
        for (std::uint32_t r = 0; r < recordCount(updated); ++r) {
            const glm::vec3 a = updated.record(r, rays), b = fresh.record(r, rays);
            differ += sameBits(a, b) ? 0 : 1;
            lit += a.x > 0 ? 1 : 0;
        }
        EXPECT_EQ(differ, 0u);
        EXPECT_GT(lit, recordCount(updated) / 4);
        if (s == &camera) {
            // The camera alone: every record kept as it was.
            EXPECT_EQ(updated.recordsTraced(), tracedBefore);
            EXPECT_EQ(updated.recordsUpdated(), updatedBefore);
        } else {
            // Brought up to date, not traced anew, but for the sites on the moved box.
            EXPECT_GT(updated.recordsUpdated() - updatedBefore, recordCount(updated) / 2);
            EXPECT_LT(updated.recordsTraced() - tracedBefore, recordCount(updated) / 4);
        }
    }
}

// A record is the same whichever client computes it and in whatever order: two caches of
// one state, filled in opposite orders from different threads, hold the same bits.
TEST(IrradianceCache, ARecordIsTheSameOnEveryClient) {
    Epochs a(cacheBox()), b(cacheBox());
    const SceneState state = SceneState::of(a.scene());
    const auto& ca = *a.begin(state).stable();
    const auto& cb = *b.begin(state).stable();
    const std::uint32_t n = recordCount(ca);
    std::vector<std::thread> threads;
    for (std::uint32_t part = 0; part < 2; ++part)
        threads.emplace_back([&, part] {
            RayCounters rays;
            for (std::uint32_t i = part; i < n; i += 2) cb.record(n - 1 - i, rays);
        });
    for (auto& t : threads) t.join();
    RayCounters rays;
    for (std::uint32_t r = 0; r < n; ++r)
        ASSERT_TRUE(sameBits(ca.record(r, rays), cb.record(r, rays)));
}

// Interpolated records agree with the light computed at the point itself (the VPLs' light is
// smooth away from creases): within a few percent on the open floor.
TEST(IrradianceCache, InterpolationAgreesWithThePointsOwnLight) {
    Epochs client(cacheBox());
    const auto& cache = *client.begin(SceneState::of(client.scene())).stable();
    RayCounters rays;
    double interpolated = 0, own = 0;
    for (float x = 0.1f; x < 0.45f; x += 0.05f)
        for (float z = 0.55f; z < 0.9f; z += 0.05f) {
            const glm::vec3 p(x, 0.0f, z), up(0, 1, 0);
            interpolated += cache.irradiance(p, up, rays).x;
            own += cache.irradianceAt(p, up, rays).x;
        }
    ASSERT_GT(own, 0.0);
    EXPECT_NEAR(interpolated / own, 1.0, 0.03);
}

}  // namespace
}  // namespace igi
