// A soft sun's disk is seen in the sky (SunDisk): by the camera, in mirrors, and by glossy
// lobes, which weigh it against the sun's light samples (issue 35).

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "lights/Lights.h"
#include "math/Color.h"
#include "testing/TestScenes.h"
#include "tracing/SunDisk.h"

namespace igi {
namespace {

using testing::InProcessRenderer;

constexpr float kIrradiance = 3.0f;

PunctualLight sunFrom(glm::vec3 toSun, float angleDeg) {
    PunctualLight l;
    l.name = "sun";
    l.kind = LightKind::Directional;
    l.direction = -glm::normalize(toSun);
    l.intensity = glm::vec3(kIrradiance);
    l.angleDeg = angleDeg;
    return l;
}

// The radiance of a disk of angular diameter angleDeg that gives irradiance E to a surface
// facing it: E = L pi sin^2(half), in double.
double diskRadiance(float angleDeg) {
    const double half = 0.5 * double(angleDeg) * 3.14159265358979 / 180.0;
    return double(kIrradiance) / (3.14159265358979 * std::sin(half) * std::sin(half));
}

// A floor out of view, so that the scene has a size; the camera at the origin looks along
// `view` through a 1 degree field, all of it inside a 4 degree disk when it looks at the sun.
Scene skyView(glm::vec3 view, const PunctualLight& sun, IntegratorKind integrator) {
    Scene scene;
    scene.materials.push_back(testing::diffuse(glm::vec3(0.5f)));
    scene.meshes.push_back(testing::makeQuad({-1, -2, -1}, {0, 0, 2}, {2, 0, 0}, 0));
    scene.punctualLights.push_back(sun);
    scene.camera = {glm::vec3(0.0f), view, glm::vec3(0, 1, 0), 1.0f};
    scene.image = {8, 8, 0};
    scene.render.causticPhotons = 0;
    scene.render.integrator = integrator;
    scene.render.pathSamples = 1;
    return scene;
}

class VisibleSun : public ::testing::TestWithParam<IntegratorKind> {};

TEST_P(VisibleSun, ACameraLookingAtASoftSunSeesItsRadianceEOverPiSinSquaredHalfAngle) {
    const glm::vec3 toSun = glm::normalize(glm::vec3(1.0f, 0.5f, 0.2f));
    InProcessRenderer renderer(skyView(toSun, sunFrom(toSun, 4.0f), GetParam()));
    const Image image = renderer.render(1);
    const double expected = diskRadiance(4.0f);
    for (const glm::vec3& p : image.pixels) ASSERT_NEAR(p.x / expected, 1.0, 1e-4);
    // Beside the disk the sky is black.
    const glm::vec3 away = glm::normalize(glm::vec3(1.0f, 0.7f, 0.2f));  // 8.6 degrees off
    InProcessRenderer beside(skyView(away, sunFrom(toSun, 4.0f), GetParam()));
    for (const glm::vec3& p : beside.render(1).pixels) ASSERT_EQ(p.x, 0.0f);
}

TEST_P(VisibleSun, ADeltaSunStaysInvisible) {
    const glm::vec3 toSun = glm::normalize(glm::vec3(1.0f, 0.5f, 0.2f));
    InProcessRenderer renderer(skyView(toSun, sunFrom(toSun, 0.0f), GetParam()));
    for (const glm::vec3& p : renderer.render(1).pixels) ASSERT_EQ(p.x, 0.0f);
}

// A mirror floor seen at the sun's reflection: every pixel is the mirror's reflectance times
// the disk's radiance.
TEST_P(VisibleSun, AMirrorReflectsTheDisk) {
    const glm::vec3 toSun = glm::normalize(glm::vec3(1.0f, 0.6f, 0.0f));
    Scene scene = skyView(toSun, sunFrom(toSun, 4.0f), GetParam());
    Material mirror = testing::diffuse(glm::vec3(0.0f));
    mirror.reflection = Reflection::Mirror;
    mirror.specular = glm::vec3(0.8f);
    scene.materials = {mirror};
    scene.meshes = {testing::makeQuad({-4, 0, -4}, {0, 0, 8}, {8, 0, 0}, 0)};
    // The camera sees the floor's centre along the reflected direction.
    const glm::vec3 down(toSun.x, -toSun.y, toSun.z);
    scene.camera = {-2.0f * down, glm::vec3(0.0f), glm::vec3(0, 1, 0), 1.0f};
    InProcessRenderer renderer(scene);
    const double expected = 0.8 * diskRadiance(4.0f);
    for (const glm::vec3& p : renderer.render(1).pixels) ASSERT_NEAR(p.x / expected, 1.0, 1e-4);
}

INSTANTIATE_TEST_SUITE_P(Integrators, VisibleSun,
                         ::testing::Values(IntegratorKind::Igi, IntegratorKind::Path),
                         [](const auto& info) {
                             return info.param == IntegratorKind::Path ? "PathTracer" : "Igi";
                         });

TEST(SunDisk, ALightSampleOfASoftSunHasTheDisksRadianceAndTheConesDensity) {
    Scene scene = skyView({1, 0, 0}, sunFrom({0.3f, 1.0f, 0.1f}, 10.0f), IntegratorKind::Igi);
    EmbreeDevice device;
    SceneGeometry geometry(device, scene);
    TraceableScene traceable(geometry);
    const Lights lights(traceable, scene.punctualLights);
    ASSERT_EQ(traceable.suns().size(), 1u);
    const SunDisk& disk = traceable.suns()[0];
    EXPECT_NEAR(disk.radiance.x / diskRadiance(10.0f), 1.0, 1e-5);
    const float distance = 0.5f * traceable.diagonal() * (1.0f + kSunDistance);
    for (const glm::vec2 u : {glm::vec2(0.1f, 0.9f), glm::vec2(0.5f), glm::vec2(0.99f, 0.01f)}) {
        const LightSample s = lights.sample(0.5f, u);
        ASSERT_TRUE(s.directional && !s.isPoint);
        EXPECT_TRUE(disk.contains(-s.direction));
        EXPECT_EQ(s.emitted, disk.radiance);
        // Area density on the far sphere times distance^2: the cone's 1 / solid angle.
        EXPECT_NEAR(s.pdf * distance * distance * disk.solidAngle(), 1.0, 1e-5);
        // Light paths still carry the sun's irradiance.
        EXPECT_NEAR(s.irradiance.x / kIrradiance, 2.0 / (2.0 - disk.oneMinusCos), 1e-6);
    }
    // Off, or without an angle, a sun has no disk.
    scene.punctualLights[0].on = false;
    EXPECT_TRUE(sunDisksOf(scene.punctualLights).empty());
    scene.punctualLights[0].on = true;
    scene.punctualLights[0].angleDeg = 0.0f;
    EXPECT_TRUE(sunDisksOf(scene.punctualLights).empty());
}

TEST(SunDisk, TheRealSunsHalfDegreeIsTestedToItsEdge) {
    SunDisk d = *sunDiskOf(sunFrom({0, 1, 0}, 0.53f));
    const float half = 0.5f * glm::radians(0.53f);
    auto at = [](float angle) { return glm::vec3(std::sin(angle), std::cos(angle), 0.0f); };
    EXPECT_TRUE(d.contains(at(0.99f * half)));
    EXPECT_FALSE(d.contains(at(1.01f * half)));
}

// A glossy (GGX) floor under a 10 degree sun, seen at the sun's reflection: the highlight is
// the disk seen through the lobe. IGI (light samples at the end point, the glossy
// continuation weighed against them) and the path tracer (next-event estimation and BRDF
// sampling with MIS) agree; counting the disk twice, or not at all, would not.
TEST(GlossyUnderASoftSun, IgiAndThePathTracerAgreeOnAGlossyFloorUnderASoftSun) {
    const glm::vec3 toSun = glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f));
    Scene scene;
    Material glossy = testing::diffuse(glm::vec3(0.3f));
    glossy.reflection = Reflection::Ggx;
    glossy.roughness = 0.3f;
    glossy.metallic = 0.0f;
    glossy.specular = glm::vec3(1.0f);
    scene.materials.push_back(glossy);
    scene.meshes.push_back(testing::makeQuad({-4, 0, -4}, {0, 0, 8}, {8, 0, 0}, 0));
    scene.punctualLights.push_back(sunFrom(toSun, 10.0f));
    scene.camera = {glm::vec3(-2, 2, 0), glm::vec3(0.0f), glm::vec3(0, 1, 0), 40};
    scene.image = {32, 24, 0};
    scene.render.causticPhotons = 0;
    const testing::IgiAndPathImages r = testing::renderIgiAndPath(scene, 32, 256);
    EXPECT_EQ(r.nonFinite, 0u);
    const double ma = r.igiMean().y, mb = r.pathMean().y;
    // The diffuse part alone (albedo / pi E cos 45 over the whole floor) for scale: the
    // highlight must be a good part of the image for the comparison to mean anything.
    const double diffuseOnly = 0.3 / 3.14159265 * kIrradiance * std::sqrt(0.5);
    std::printf("glossy floor under a soft sun: igi %.5f, path tracer %.5f, diffuse %.5f\n", ma, mb,
                diffuseOnly);
    EXPECT_GT(ma, 1.3 * diffuseOnly);
    EXPECT_NEAR(ma / mb, 1.0, 0.02);
}

}  // namespace
}  // namespace igi
