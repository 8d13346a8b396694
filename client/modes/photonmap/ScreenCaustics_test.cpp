#include "modes/photonmap/ScreenCaustics.h"

#include <cmath>

#include <gtest/gtest.h>

#include "testing/TestScenes.h"
#include "tracing/EmbreeDevice.h"
#include "tracing/SceneGeometry.h"

namespace igi {
namespace {

// A floor seen from above at an angle, a box standing on it, and a camera.
Scene floorScene() {
    Scene scene;
    scene.materials = {testing::diffuse(glm::vec3(0.5f))};
    scene.meshes = {testing::makeQuad({-2, 0, 2}, {4, 0, 0}, {0, 0, -4}, 0),
                    testing::makeBox({0.8f, 0.3f, 0.0f}, glm::vec3(0.3f), 0.0f, 0)};
    scene.camera = {{0, 2.5f, 2.0f}, {0, 0, 0}, {0, 1, 0}, 50};
    return scene;
}

// The energy the filter spreads over the pixels (irradiance times each pixel's footprint)
// is the flux of the photons the camera sees: within 2 % for a caustic on an oblique floor,
// nothing for photons behind the box, and nothing from the floor's underside.
TEST(ScreenCaustics, TheFilterKeepsACausticsEnergy) {
    const Scene scene = floorScene();
    EmbreeDevice device;
    SceneGeometry geometry(device, scene);
    TraceableScene traceable(geometry);
    const int w = 160, h = 120;
    std::vector<CausticPhoton> photons;
    SplitMix64 random(3);
    double seenFlux = 0;
    for (int i = 0; i < 2000; ++i) {
        // A ring-shaped caustic on the floor in front of the box.
        const float a = 6.2831853f * random.uniform(), r = 0.3f + 0.05f * random.uniform();
        const glm::vec3 p(-0.3f + r * std::cos(a), 0.0f, 0.4f + r * std::sin(a));
        const glm::vec3 power(1e-3f * (1.0f + random.uniform()));
        photons.push_back({p, {0, -1, 0}, power, {0, 1, 0}});
        seenFlux += power.x;
    }
    // Behind the box (hidden from the camera), and under the floor (the other side).
    photons.push_back({{0.8f, 0.0f, -0.45f}, {0, -1, 0}, glm::vec3(1.0f), {0, 1, 0}});
    photons.push_back({{-0.5f, 0.0f, 0.5f}, {0, 1, 0}, glm::vec3(1.0f), {0, -1, 0}});
    const ScreenCaustics filter(traceable, scene.camera, w, h, photons);
    const CameraModel camera(scene.camera, w, h);
    RayCounters rays;
    double energy = 0;
    int lit = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            SurfacePoint hit;
            const glm::vec3 dir = camera.direction(float(x) + 0.5f, float(y) + 0.5f);
            if (!traceable.intersect(camera.origin(), dir, 1e30f, hit, rays)) continue;
            const float area = filter.footprint(x, y, hit.distance, hit.geometricNormal);
            const glm::vec3 e = filter.irradiance(x, y, area, rays);
            energy += double(e.x) * double(area);
            lit += e.x > 0 ? 1 : 0;
        }
    EXPECT_NEAR(energy / seenFlux, 1.0, 0.02);
    EXPECT_GT(lit, 200);  // spread over the ring's pixels and their neighbours
}

// The weights are the paper's: a photon alone in the middle of the image lights the 7 x 7
// pixels around its own, the most at the centre, sqrt(1 + 2 k^2 - (i^2 + j^2)) in proportion.
TEST(ScreenCaustics, WeightsAreThePapers) {
    Scene scene;
    scene.materials = {testing::diffuse(glm::vec3(0.5f))};
    scene.meshes = {testing::makeQuad({-5, -5, 0}, {10, 0, 0}, {0, 10, 0}, 0)};
    scene.camera = {{0, 0, 3}, {0, 0, 0}, {0, 1, 0}, 40};
    EmbreeDevice device;
    SceneGeometry geometry(device, scene);
    TraceableScene traceable(geometry);
    const int w = 64, h = 64;
    const CameraModel camera(scene.camera, w, h);
    // The point pixel (32, 32)'s centre sees on the plane.
    const glm::vec3 d = camera.direction(32.5f, 32.5f);
    const glm::vec3 p = camera.origin() + d * (3.0f / -d.z);
    const ScreenCaustics filter(traceable, scene.camera, w, h,
                                {{p, {0, 0, -1}, glm::vec3(1.0f), {0, 0, 1}}});
    RayCounters rays;
    auto flux = [&](int x, int y) { return filter.irradiance(x, y, 1.0f, rays).x; };
    EXPECT_EQ(flux(32 + 4, 32), 0.0f);
    EXPECT_GT(flux(32 + 3, 32 + 3), 0.0f);
    EXPECT_NEAR(flux(32, 32) / flux(32 + 3, 32 + 3), std::sqrt(19.0f / 1.0f), 1e-4f);
    EXPECT_NEAR(flux(32 + 1, 32) / flux(32 + 2, 32 + 2), std::sqrt(18.0f / 11.0f), 1e-4f);
    double total = 0;
    for (int y = 25; y < 40; ++y)
        for (int x = 25; x < 40; ++x) total += flux(x, y);
    EXPECT_NEAR(total, 1.0, 1e-5);
}

}  // namespace
}  // namespace igi
