// Where the light paths of a sun (and of the environment) start: on the rectangle across the
// light that the scene's box fills, not on the disk of its bounding sphere, most of which an
// elongated scene leaves empty (Lights::parallelStart).
#include <cmath>
#include <cstddef>
#include <limits>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "lighting/LightingSetBuilder.h"
#include "lights/Lights.h"
#include "testing/TestScenes.h"

namespace igi {
namespace {

using testing::InProcessRenderer;

constexpr float kLength = 16.0f, kWidth = 1.0f, kIrradiance = 2.0f, kAlbedo = 0.7f;

// A diffuse floor 16 long and 1 wide under a sun from straight above: its bounding sphere's
// disk (radius 8.02) is 12.6 times the floor's area.
Scene longFloorUnderASun(glm::vec3 direction) {
    Scene scene;
    scene.materials.push_back(testing::diffuse(glm::vec3(kAlbedo)));
    scene.meshes.push_back(testing::makeQuad({-0.5f * kLength, 0, -0.5f * kWidth}, {0, 0, kWidth},
                                             {kLength, 0, 0}, 0));
    PunctualLight sun;
    sun.name = "sun";
    sun.kind = LightKind::Directional;
    sun.direction = glm::normalize(direction);
    sun.intensity = glm::vec3(kIrradiance);
    scene.punctualLights.push_back(sun);
    scene.camera = {{0, 3, 2}, {0, 0, 0}, {0, 1, 0}, 60};
    scene.image = {16, 12, 0};
    scene.render.causticPhotons = 0;
    return scene;
}

TEST(ParallelStart, EveryLineThatMeetsTheSceneCrossesItsRectangle) {
    // Starts on a grid over the rectangle: the share whose parallel ray meets the floor, times
    // the rectangle's area, is the floor's area seen along the light (A cos theta), overhead and
    // tilted; nothing is left out (that would be light lost) and, overhead, nothing is wasted.
    for (const glm::vec3 d : {glm::vec3(0, -1, 0), glm::normalize(glm::vec3(0.3f, -1, 0.2f))}) {
        const Scene scene = longFloorUnderASun(d);
        EmbreeDevice device;
        SceneGeometry geometry(device, scene);
        TraceableScene traceable(geometry);
        const Lights lights(traceable, scene.punctualLights);
        const int n = 200;
        int hits = 0;
        float area = 0;
        RayCounters rays;
        SurfacePoint hit;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                const Lights::ParallelStart s =
                    lights.parallelStart(d, {(float(i) + 0.5f) / n, (float(j) + 0.5f) / n});
                area = s.area;
                // Outside the bounding sphere, so that nothing in the scene is behind the start.
                EXPECT_GT(glm::length(s.origin - traceable.center()), 0.5f * traceable.diagonal());
                hits += traceable.intersect(s.origin, d, std::numeric_limits<float>::infinity(),
                                            hit, rays);
            }
        const float seen = area * float(hits) / float(n * n);
        EXPECT_NEAR(seen / (kLength * kWidth * -d.y), 1.0f, 0.01f) << d.x;
        EXPECT_LE(area, lights.diskArea());
        if (d.y == -1.0f) {  // the rectangle is the floor itself
            EXPECT_NEAR(area, kLength * kWidth, 1e-3f);
            EXPECT_GE(hits, n * n * 99 / 100);
        }
    }
}

TEST(ParallelStart, NearlyEveryLightPathOfASunOverALongFloorLeavesAVpl) {
    // From the bounding sphere's disk 1 path in 12.6 would meet the floor (the rest are VPLs
    // that never were, and noise in every pixel that shares the set); from the rectangle, all.
    // The light they carry is still the floor's: E A kd / pi in VPL power per set.
    InProcessRenderer r(longFloorUnderASun({0, -1, 0}));
    std::size_t vpls = 0, paths = 0;
    double power = 0;
    const std::uint32_t sets = 9;
    for (std::uint32_t k = 0; k < sets; ++k) {
        const LightingSet set = r.renderer().builder().build(3, 1, k);
        vpls += set.indirect.size();  // a floor cannot light itself: one VPL per path that hit
        paths += set.lightPaths;
        for (const Vpl& v : set.indirect) power += double(v.power.x);
    }
    ASSERT_GT(paths, 0u);
    EXPECT_GE(double(vpls), 0.95 * double(paths));
    const double expected = kIrradiance * kLength * kWidth * kAlbedo / M_PI;
    EXPECT_NEAR(power / sets / expected, 1.0, 0.02);
}

}  // namespace
}  // namespace igi
