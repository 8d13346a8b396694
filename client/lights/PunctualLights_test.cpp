// Directional (sun) and spot lights: their direct light against closed forms, their light
// paths against the path tracer, and their extremes (issue 35).

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "lights/Lights.h"
#include "math/Color.h"
#include "math/Warp.h"
#include "scene/CameraModel.h"
#include "testing/TestScenes.h"

namespace igi {
namespace {

using testing::InProcessRenderer;

constexpr float kAlbedo = 0.5f;

using testing::sun;

PunctualLight spot(glm::vec3 position, glm::vec3 direction, float intensity, float innerDeg,
                   float outerDeg) {
    PunctualLight l;
    l.name = "spot";
    l.kind = LightKind::Spot;
    l.position = position;
    l.direction = glm::normalize(direction);
    l.intensity = glm::vec3(intensity);
    l.innerDeg = innerDeg;
    l.outerDeg = outerDeg;
    return l;
}

// A diffuse floor (facing +y) of half-size 2 s around `offset`, seen straight from above from
// height s: nothing but the floor is in view, and a floor cannot light itself, so every pixel
// shows the direct light alone.
Scene floorSeenFromAbove(float s, glm::vec3 offset) {
    Scene scene;
    scene.materials.push_back(testing::diffuse(glm::vec3(kAlbedo)));
    scene.meshes.push_back(testing::makeQuad(offset + s * glm::vec3(-2, 0, -2),
                                             s * glm::vec3(0, 0, 4), s * glm::vec3(4, 0, 0), 0));
    scene.camera = {offset + glm::vec3(0, s, 0), offset, glm::vec3(0, 0, -1), 40};
    scene.image = {32, 24, 0};
    scene.render.causticPhotons = 0;
    return scene;
}

struct SunCase {
    IntegratorKind integrator;
    float scale;
    float irradiance;
    float offset;  ///< of the whole scene from the origin, in x and z
    float angleDeg;
};

void PrintTo(const SunCase& c, std::ostream* os) {
    *os << (c.integrator == IntegratorKind::Path ? "path" : "igi") << " scale " << c.scale << " E "
        << c.irradiance << " offset " << c.offset << " angle " << c.angleDeg;
}

class SunOnAFloor : public ::testing::TestWithParam<SunCase> {};

// A sun 60 degrees from the zenith gives the floor irradiance E cos 60 = E / 2 everywhere, and
// a soft sun the same (the cosine-weighted integral over a disk of directions is linear in
// the normal): every pixel's radiance is albedo / pi * E / 2.
TEST_P(SunOnAFloor, EveryPixelHasRadianceAlbedoOverPiTimesECosTheta) {
    const SunCase c = GetParam();
    Scene scene = floorSeenFromAbove(c.scale, glm::vec3(c.offset, 0, c.offset));
    const float theta = glm::radians(60.0f);
    scene.punctualLights.push_back(
        sun({std::sin(theta), -std::cos(theta), 0.0f}, c.irradiance, c.angleDeg));
    scene.render.integrator = c.integrator;
    scene.render.pathSamples = 4;
    const bool soft = c.angleDeg > 0;
    InProcessRenderer renderer(scene);
    const Image image = renderer.render(soft ? 16 : 1);
    const double expected = kAlbedo / kPi * c.irradiance * 0.5;
    const glm::dvec3 mean = testing::meanOf(image);
    EXPECT_NEAR(mean.x / expected, 1.0, soft ? 0.01 : 1e-3);
    for (const auto& p : image.pixels) {
        ASSERT_TRUE(isFinite(p));
        // A delta sun is exact at every pixel; a soft one's samples vary with the direction.
        ASSERT_NEAR(p.y / expected, 1.0, soft ? 0.1 : 2e-3);
    }
}

INSTANTIATE_TEST_SUITE_P(Cases, SunOnAFloor,
                         ::testing::Values(SunCase{IntegratorKind::Igi, 1.0f, 1.0f, 0.0f, 0.0f},
                                           SunCase{IntegratorKind::Igi, 1e-3f, 1e-6f, 0.0f, 0.0f},
                                           SunCase{IntegratorKind::Igi, 1e3f, 1e6f, 0.0f, 0.0f},
                                           SunCase{IntegratorKind::Igi, 1.0f, 1.0f, 1e5f, 0.0f},
                                           SunCase{IntegratorKind::Igi, 1.0f, 1.0f, 0.0f, 20.0f},
                                           SunCase{IntegratorKind::Path, 1.0f, 1.0f, 0.0f, 0.0f},
                                           SunCase{IntegratorKind::Path, 1e3f, 1e6f, 1e5f, 0.0f},
                                           SunCase{IntegratorKind::Path, 1.0f, 1.0f, 0.0f, 20.0f}));

// A spot at height h straight above the floor's centre: the floor point at angle a from the axis
// receives I ramp(cos a) cos a / (h / cos a)^2.
void expectSpotFalloff(IntegratorKind integrator) {
    const float h = 1.0f, inner = 10.0f, outer = 35.0f, intensity = 3.0f;
    Scene scene = floorSeenFromAbove(1.0f, glm::vec3(0.0f));
    const float eye = 2.2f * h;
    scene.camera.position = glm::vec3(0, eye, 0);
    scene.camera.fovYDeg = 40;
    scene.image = {64, 48, 0};
    scene.punctualLights.push_back(spot({0, h, 0}, {0, -1, 0}, intensity, inner, outer));
    scene.render.integrator = integrator;
    scene.render.pathSamples = 2;
    // One set of lights for every pixel, so no filter averages the ramp across pixels.
    scene.render.interleaveX = scene.render.interleaveY = 1;
    InProcessRenderer renderer(scene);
    const Image image = renderer.render(1);
    const PunctualLight& light = scene.punctualLights[0];
    const CameraModel camera(scene.camera, scene.image.width, scene.image.height);
    auto radianceAt = [&](float px, float py) {
        const glm::dvec3 d(camera.direction(px, py));
        const glm::dvec3 p = glm::dvec3(scene.camera.position) + (-double(eye) / d.y) * d;
        const double r2 = p.x * p.x + p.z * p.z + double(h) * h;
        const double cosA = h / std::sqrt(r2);
        return kAlbedo / kPi * intensity * spotFalloff(light, float(cosA)) * cosA / r2;
    };
    // The least radiance inside the inner cone (at its edge).
    const double peak =
        kAlbedo / kPi * intensity * std::pow(std::cos(glm::radians(inner)), 3) / (h * h);
    int full = 0, dark = 0, ramp = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            // The pixel's value lies between the least and the most the radiance is over the
            // pixel (wherever in it the camera's rays went), with 1 % to spare.
            double lo = HUGE_VAL, hi = 0.0;
            for (float dy : {0.0f, 0.5f, 1.0f})
                for (float dx : {0.0f, 0.5f, 1.0f}) {
                    const double r = radianceAt(x + dx, y + dy);
                    lo = std::min(lo, r), hi = std::max(hi, r);
                }
            const double got = image.at(x, y).x;
            if (hi == 0.0) {
                ++dark;
                EXPECT_EQ(got, 0.0) << "(" << x << ", " << y << ") outside the outer cone";
                continue;
            }
            (lo >= peak * 0.999 ? full : ramp)++;
            EXPECT_GE(got, lo * 0.99) << "(" << x << ", " << y << ")";
            EXPECT_LE(got, hi * 1.01) << "(" << x << ", " << y << ")";
        }
    std::printf("spot: %d pixels in the full cone, %d on the ramp, %d dark\n", full, ramp, dark);
    EXPECT_GT(full, 20);
    EXPECT_GT(ramp, 20);
    EXPECT_GT(dark, 20);
}

TEST(SpotLight, IgiFollowsTheGltfRampBetweenItsCones) {
    expectSpotFalloff(IntegratorKind::Igi);
}

TEST(SpotLight, ThePathTracerFollowsTheSameRamp) {
    expectSpotFalloff(IntegratorKind::Path);
}

TEST(SpotLight, RampIsOneInsideZeroOutsideAndTheSpecificationsBetween) {
    PunctualLight l = spot({0, 0, 0}, {0, -1, 0}, 1.0f, 20.0f, 40.0f);
    const float ci = std::cos(glm::radians(20.0f)), co = std::cos(glm::radians(40.0f));
    EXPECT_FLOAT_EQ(spotFalloff(l, 1.0f), 1.0f);
    EXPECT_FLOAT_EQ(spotFalloff(l, ci), 1.0f);
    EXPECT_FLOAT_EQ(spotFalloff(l, co), 0.0f);
    EXPECT_FLOAT_EQ(spotFalloff(l, -1.0f), 0.0f);
    const float mid = 0.5f * (ci + co);
    EXPECT_NEAR(spotFalloff(l, mid), 0.25f, 1e-5f);  // (1/2)^2
    l.innerDeg = l.outerDeg;                         // a hard edge stays finite
    EXPECT_TRUE(std::isfinite(spotFalloff(l, co + 1e-4f)));
}

// An open corner (a floor and a wall) in sunlight, with a spot and a point light beside: each
// surface lights the other, so IGI's VPLs must carry each light's power into the scene as the
// path tracer's paths do. Converged, the two agree.
Scene sunlitCorner() {
    Scene scene;
    scene.materials.push_back(testing::diffuse(glm::vec3(0.7f)));
    scene.meshes.push_back(testing::makeQuad({-1, 0, -1}, {0, 0, 2}, {2, 0, 0}, 0));  // floor
    scene.meshes.push_back(testing::makeQuad({-1, 0, -1}, {2, 0, 0}, {0, 2, 0}, 0));  // wall, +z
    scene.punctualLights.push_back(sun({0.4f, -1.0f, -0.6f}, 2.0f, 0.5f));
    scene.punctualLights.push_back(spot({0.5f, 1.2f, 0.6f}, {-0.3f, -1.0f, -0.4f}, 1.5f, 10, 30));
    scene.punctualLights.push_back(pointLight("lamp", {-0.6f, 0.4f, 0.5f}, glm::vec3(0.05f)));
    scene.camera = {{0.2f, 1.0f, 2.6f}, {0, 0.4f, -0.5f}, {0, 1, 0}, 50};
    scene.image = {32, 24, 0};
    scene.render.causticPhotons = 0;
    scene.render.maxLightPathLength = 16;
    scene.render.maxPathLength = 16;
    return scene;
}

TEST(SunlitCorner, ConvergedIgiMatchesThePathTracer) {
    Scene scene = sunlitCorner();
    const testing::IgiAndPathImages r = testing::renderIgiAndPath(scene, 32, 256);
    const glm::dvec3 a = r.igiMean(), b = r.pathMean();
    std::printf("sunlit corner: igi %.5f, path tracer %.5f\n", a.x, b.x);
    EXPECT_NEAR(a.x / b.x, 1.0, 0.02);
    // Without the VPLs' light (direct only) IGI is clearly darker: the test sees indirect light.
    scene.render.integrator = IntegratorKind::Igi;
    scene.render.maxLightPathLength = 1;
    scene.render.roulette = false;
    InProcessRenderer direct(scene);
    EXPECT_LT(testing::meanOf(direct.render(4)).x / b.x, 0.95);
}

TEST(Lights, ASunBesideALampLeavesTheLampHalfTheLightPathsAtLeast) {
    // A 1e5 W/m^2 sun would take every light path from a lamp of 1 W/sr by power alone.
    Scene scene = sunlitCorner();
    scene.punctualLights.resize(1);
    scene.punctualLights[0].intensity = glm::vec3(1e5f);
    scene.punctualLights.push_back(pointLight("lamp", {-0.6f, 0.4f, 0.5f}, glm::vec3(1.0f)));
    EmbreeDevice device;
    SceneGeometry geometry(device, scene);
    TraceableScene traceable(geometry);
    const Lights lights(traceable, scene.punctualLights);
    int lamp = 0;
    const int n = 1000;
    for (int i = 0; i < n; ++i) lamp += !lights.sample((i + 0.5f) / n, {0.5f, 0.5f}).directional;
    EXPECT_GE(lamp, n / 4);  // half of the uniform half
    EXPECT_LE(lamp, n / 2);
}

TEST(Lights, ADirectionalSampleIsAFarPointGivingTheIrradiance) {
    Scene scene = sunlitCorner();
    scene.punctualLights.resize(1);
    scene.punctualLights[0].angleDeg = 0.0f;
    EmbreeDevice device;
    SceneGeometry geometry(device, scene);
    TraceableScene traceable(geometry);
    const Lights lights(traceable, scene.punctualLights);
    const LightSample s = lights.sample(0.5f, {0.3f, 0.7f});
    ASSERT_TRUE(s.directional && s.isPoint);
    EXPECT_FLOAT_EQ(s.pdf, 1.0f);
    // At any point of the scene, intensity / d^2 is the irradiance within 1e-4.
    for (const glm::vec3 p : {glm::vec3(-1, 0, -1), glm::vec3(1, 2, 1), glm::vec3(0)}) {
        const glm::vec3 toLight = s.position - p;
        const float e = s.emitted.x / glm::dot(toLight, toLight);
        EXPECT_NEAR(e / 2.0f, 1.0f, 1e-4f);
        EXPECT_GT(glm::dot(glm::normalize(toLight), -s.direction), 1.0f - 1e-6f);
    }
    // Light paths start outside the scene's bounding sphere, on a disk across the light.
    const float radius = 0.5f * traceable.diagonal();
    for (const glm::vec2 u : {glm::vec2(0.1f, 0.9f), glm::vec2(0.5f), glm::vec2(0.99f, 0.01f)}) {
        const glm::vec3 o = lights.diskOrigin(s.direction, u);
        EXPECT_GT(glm::length(o - traceable.center()), radius);
        const glm::vec3 offset = o - traceable.center();
        const glm::vec3 across = offset - glm::dot(offset, s.direction) * s.direction;
        EXPECT_LE(glm::length(across), radius * 1.0001f);
        EXPECT_LT(glm::dot(offset, s.direction), 0.0f);  // upstream
    }
}

}  // namespace
}  // namespace igi
