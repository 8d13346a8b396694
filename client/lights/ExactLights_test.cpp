// Exact lights (client/lights/Lights.h): a scene's few point, spot and sun lights are each one
// shadow ray of every receiving point, never chosen among the other lights, and their light
// reaches the master unfiltered.

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "integrators/IgiIntegrator.h"
#include "lights/Lights.h"
#include "math/Color.h"
#include "testing/TestScenes.h"

namespace igi {
namespace {

using testing::InProcessRenderer;

constexpr float kAlbedo = 0.5f;

// A diffuse floor (facing +y) seen straight from above, under a delta sun 60 degrees from the
// zenith and a constant sky: the floor's only light. The camera sees nothing but the floor.
Scene floorUnderSunAndSky() {
    Scene scene;
    scene.materials.push_back(testing::diffuse(glm::vec3(kAlbedo)));
    scene.meshes.push_back(testing::makeQuad({-2, 0, -2}, {0, 0, 4}, {4, 0, 0}, 0));
    scene.camera = {{0, 1, 0}, {0, 0, 0}, {0, 0, -1}, 40};
    scene.image = {12, 9, 0};
    scene.render.causticPhotons = 0;
    const float theta = glm::radians(60.0f);
    scene.punctualLights.push_back(testing::sun({std::sin(theta), -std::cos(theta), 0.0f}, 3.0f));
    scene.environment.radiance = glm::vec3(0.2f);
    return scene;
}

struct Built {
    EmbreeDevice device;
    SceneGeometry geometry;
    TraceableScene traceable;
    explicit Built(const Scene& scene) : geometry(device, scene), traceable(geometry) {}
};

// An emissive quad beside the punctual lights: the quad is chosen, the punctual lights are exact.
Scene quadAndPunctualLights(int punctual) {
    Scene scene = floorUnderSunAndSky();
    scene.environment.radiance = glm::vec3(0.0f);
    scene.punctualLights.clear();
    Material lamp = testing::diffuse(glm::vec3(0.0f));
    lamp.emission = glm::vec3(4.0f);
    scene.materials.push_back(lamp);
    scene.meshes.push_back(testing::makeQuad({-0.2f, 1.5f, -0.2f}, {0.4f, 0, 0}, {0, 0, 0.4f}, 1));
    for (int i = 0; i < punctual; ++i)
        scene.punctualLights.push_back(
            pointLight("lamp", {0.3f * float(i), 1.0f, 0.0f}, glm::vec3(0.5f)));
    return scene;
}

TEST(ExactLights, AFewPunctualLightsAreExactAndReceiversChooseOnlyTheOthers) {
    for (int punctual : {1, int(kMaxExactLights)}) {
        const Scene scene = quadAndPunctualLights(punctual);
        Built b(scene);
        const Lights lights(b.traceable, scene.punctualLights);
        ASSERT_EQ(lights.exactLights(), std::size_t(punctual));
        ASSERT_TRUE(lights.receiversChoose());
        for (std::size_t k = 0; k < lights.exactLights(); ++k) {
            const LightSample s = lights.exactLight(k, {0.5f, 0.5f});
            EXPECT_TRUE(s.isPoint);
            EXPECT_EQ(s.select, 1.0f);
            EXPECT_EQ(s.pdf, 1.0f);
        }
        const int n = 1000;
        int fromPaths = 0;
        for (int i = 0; i < n; ++i) {
            const float u = (float(i) + 0.5f) / float(n);
            const LightSample r = lights.sampleAt({0, 0, 0}, {0, 1, 0}, u, {0.3f, 0.6f});
            ASSERT_GT(r.pdf, 0.0f);
            EXPECT_FALSE(r.isPoint) << "a receiver chose an exact light";
            // The quad's two triangles are all there is to choose: half each.
            EXPECT_EQ(r.select, 0.5f);
            fromPaths += lights.sample(u, {0.3f, 0.6f}).isPoint;
        }
        // Light paths still leave every light.
        EXPECT_GT(fromPaths, 0);
        EXPECT_LT(fromPaths, n);
    }
}

TEST(ExactLights, BeyondTheLimitEveryLightIsChosen) {
    const Scene scene = quadAndPunctualLights(int(kMaxExactLights) + 1);
    Built b(scene);
    const Lights lights(b.traceable, scene.punctualLights);
    EXPECT_EQ(lights.exactLights(), 0u);
    int points = 0;
    for (int i = 0; i < 100; ++i)
        points +=
            lights.sampleAt({0, 0, 0}, {0, 1, 0}, (float(i) + 0.5f) / 100.0f, {0.5f, 0.5f}).isPoint;
    EXPECT_GT(points, 0);
}

TEST(ExactLights, OnlyExactLightsLeaveReceiversNothingToChoose) {
    Scene scene = floorUnderSunAndSky();
    scene.environment.radiance = glm::vec3(0.0f);
    InProcessRenderer renderer(scene);
    bool built = false;
    const auto set = renderer.renderer().cache().get(0, 0, 0, built);
    EXPECT_EQ(set->exact.size(), 1u);
    EXPECT_TRUE(set->direct.empty());  // before: four samples, all of the sun
    EXPECT_TRUE(set->directNumbers.empty());
}

// The sun's light on the floor is E cos 60 / pi times the albedo in every set, so it goes to the
// unfiltered plane whole and alike in all nine sets of the interleaving; the sky's, sampled, goes
// to the filtered irradiance and differs from set to set.
TEST(ExactLights, TheSunlightOfEverySetIsTheSameAndUnfiltered) {
    const Scene scene = floorUnderSunAndSky();
    InProcessRenderer renderer(scene);
    TileRenderer& tiles = renderer.renderer();
    const IgiIntegrator igi(renderer.traceable(), tiles.lights(), scene.render, tiles.camera());
    const double expected = kAlbedo / kPi * 3.0 * 0.5;
    const int x = scene.image.width / 2, y = scene.image.height / 2;
    const auto index = std::uint32_t(y * scene.image.width + x);
    std::vector<float> sky;
    for (std::uint32_t k = 0; k < 9; ++k) {
        bool built = false;
        const auto set = tiles.cache().get(1, 0, k, built);
        ASSERT_EQ(set->exact.size(), 1u);
        RayCounters counters;
        const PixelResult r = igi.shade(x, y, index, 1, *set, counters);
        EXPECT_NEAR(r.unfiltered.x / expected, 1.0, 1e-4) << "set " << k;
        sky.push_back(r.irradiance.x);
    }
    bool differs = false;
    for (float s : sky) {
        EXPECT_GT(s, 0.0f);
        // The sky's irradiance on the floor is pi L: its estimate over pi stays near L.
        EXPECT_LT(s, 10 * 0.2f);
        differs |= s != sky[0];
    }
    EXPECT_TRUE(differs) << "the sky is sampled, set by set";
}

}  // namespace
}  // namespace igi
