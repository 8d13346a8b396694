// Rough glass in the renderers: a white furnace (a sphere of clear rough glass in a constant
// sky, the path tracer with its light samples and MIS through the BSDF) and IGI against the
// path tracer on the default scene with its glass ball made rough.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "image/ImageCompare.h"
#include "materials/RoughDielectric.h"
#include "math/Color.h"
#include "math/Frame.h"
#include "scene/CameraModel.h"
#include "scene/SceneLoader.h"
#include "shading/Scattering.h"
#include "testing/TestScenes.h"
#include "util/TestPaths.h"

namespace igi {
namespace {

using testing::InProcessRenderer;

Material roughGlass(float roughness) {
    Material m = testing::diffuse(glm::vec3(0.0f));
    m.glass = true;
    m.ior = 1.5f;
    m.reflection = Reflection::Ggx;
    m.roughness = roughness;
    return m;
}

// A sphere of rough glass (radius 1) in a sky of radiance 1, seen from 5 radii.
Scene roughSphereInTheSky(float roughness) {
    Scene scene;
    scene.materials.push_back(roughGlass(roughness));
    scene.meshes.push_back(testing::makeIcosphere(5, 1.0f, glm::vec3(0), 0));
    scene.environment.radiance = glm::vec3(1.0f);
    scene.camera = {glm::vec3(0, 0, 5.0f), glm::vec3(0), glm::vec3(0, 1, 0), 30};
    scene.image = {24, 18, 0};
    scene.render.causticPhotons = 0;
    scene.render.maxPathLength = 256;  // Russian roulette ends the paths, not the length
    scene.render.maxEyeDepth = 256;
    return scene;
}

// The mean over the middle of the image, on the sphere.
double sphereMean(const Image& image) {
    double sum = 0;
    int count = 0;
    for (int y = 5; y < 13; ++y)
        for (int x = 8; x < 16; ++x) sum += image.at(x, y).y, ++count;
    return sum / count;
}

// What the path tracer must converge to on the sphere's pixels: the BSDF's own random walk
// (its sampler alone, RoughDielectric.h) through an analytic unit sphere, for the camera rays
// of the pixels sphereMean averages, each path ending in the sky of 1 or lost where the
// sampler loses it (masking), with Russian roulette from the fourth bounce.
double randomWalkMean(const Scene& scene, float roughness, int pathsPerPixel) {
    const CameraModel camera(scene.camera, scene.image.width, scene.image.height);
    const float alpha = roughness * roughness;
    std::mt19937 rng(23);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    double sum = 0;
    int paths = 0;
    for (int y = 5; y < 13; ++y)
        for (int x = 8; x < 16; ++x)
            for (int k = 0; k < pathsPerPixel; ++k, ++paths) {
                glm::dvec3 o(camera.origin());
                // Unit in double: the float direction's length is 1 only to a float ULP, and
                // the root below assumes |d| = 1; the hit would land ~1e-6 off the sphere,
                // past the 1e-6 the next root must exceed, and enter the glass twice.
                const glm::dvec3 d0(camera.direction(float(x) + u(rng), float(y) + u(rng)));
                glm::dvec3 d = glm::normalize(d0);
                double throughput = 1;
                for (int bounce = 0; bounce < 1000; ++bounce) {
                    // |o + t d| = 1, the first root beyond the point the ray leaves.
                    const double b = glm::dot(o, d), c = glm::dot(o, o) - 1.0;
                    const double disc = b * b - c;
                    double t = -1;
                    if (disc > 0) {
                        const double r = std::sqrt(disc);
                        t = -b - r > 1e-6 ? -b - r : -b + r > 1e-6 ? -b + r : -1.0;
                    }
                    if (t < 0) {
                        sum += throughput;  // the sky
                        break;
                    }
                    o += t * d;
                    const glm::vec3 n(glm::normalize(o));
                    const glm::vec3 wo(-d);
                    const bool outside = glm::dot(wo, n) > 0;
                    const Frame frame(outside ? n : -n);
                    roughdielectric::Sample smp;
                    const glm::vec2 uv(u(rng), u(rng));
                    if (!roughdielectric::sampleLocal(alpha, outside ? 1.5f : 1.0f / 1.5f,
                                                      frame.toLocal(wo), uv, u(rng), smp))
                        break;
                    throughput *= smp.weight;
                    d = glm::normalize(glm::dvec3(frame.toWorld(smp.wi)));
                    if (bounce >= 3) {
                        const double q = std::min(0.95, throughput);
                        if (u(rng) >= q) break;
                        throughput /= q;
                    }
                }
            }
    return sum / paths;
}

// The same walk through the renderer's own pieces (Embree's hits on the icosphere, lobesAt,
// sampleLobe, the ray offsets) without either integrator: what separates the integrators'
// light samples, MIS, chains and number streams from the surface they walk on.
double piecesWalkMean(const Scene& scene, const TraceableScene& traceable, int pathsPerPixel) {
    const CameraModel camera(scene.camera, scene.image.width, scene.image.height);
    std::mt19937 rng(29);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    RayCounters counters;
    double sum = 0;
    int paths = 0;
    for (int y = 5; y < 13; ++y)
        for (int x = 8; x < 16; ++x)
            for (int k = 0; k < pathsPerPixel; ++k, ++paths) {
                glm::vec3 o = camera.origin();
                glm::vec3 d = camera.direction(float(x) + u(rng), float(y) + u(rng));
                double throughput = 1;
                for (int bounce = 0; bounce < 1000; ++bounce) {
                    SurfacePoint hit;
                    if (!traceable.intersect(o, d, std::numeric_limits<float>::infinity(), hit,
                                             counters)) {
                        sum += throughput;
                        break;
                    }
                    const Lobes l = lobesAt(hit, -d);
                    glm::vec3 direction, weight;
                    const glm::vec2 uv(u(rng), u(rng));
                    if (!sampleLobe(l, Lobe::Transmission, uv, u(rng), direction, weight)) break;
                    throughput *= double(weight.y);
                    d = direction;
                    o = traceable.offsetOrigin(hit.position, l.faceNormal, d);
                    if (bounce >= 3) {
                        const double q = std::min(0.95, throughput);
                        if (u(rng) >= q) break;
                        throughput /= q;
                    }
                }
            }
    return sum / paths;
}

// Non-absorbing glass in a constant sky shows the sky wherever light enters and leaves it, but
// the single-scattering microfacet model loses at every scattering the energy its sampler
// sends to the wrong side (RoughDielectric_test prints it per scattering: at alpha 1, 7 % of
// the light entering head-on, 58 % of the light leaving head-on). So the sphere converges to
// the sky less that loss, compounded over its internal scatterings: the path tracer (light
// samples and MIS through the BSDF) and IGI (the sampled continuation alone) agree with the
// BSDF's own random walk through an analytic sphere within 1 % up to roughness 0.6, never
// exceed the sky, darken with roughness, and lose under 1 % at roughness 0.2; the smooth
// sphere is exact. At roughness 0.8 and 1 the renderers were above the walk by 1.7 % and
// 3.7 %: the walk's camera rays were unit only in float, their first hit landed ~1e-6 outside
// the sphere and 12 % of the paths entered the glass twice there, losing the masking of a
// second rough interface. With unit rays in double the walk agrees with the one through the
// renderer's pieces (piecesWalkMean) path by path; the renderers are above it by 0.2 to 1.6 %
// there, by their random streams, so the test allows 2 % at those roughnesses.
TEST(RoughGlassFurnace, ASphereOfClearGlassConvergesToTheSkyLessTheSingleScatteringLoss) {
    double previous = 2.0;
    for (const float roughness : {0.0f, 0.2f, 0.4f, 0.6f, 0.8f, 1.0f}) {
        Scene scene = roughSphereInTheSky(roughness);
        scene.render.integrator = IntegratorKind::Path;
        scene.render.pathSamples = 64;
        InProcessRenderer path(scene);
        const double pathMean = sphereMean(path.render(16));
        scene.render.integrator = IntegratorKind::Igi;
        InProcessRenderer igi(scene);
        const double igiMean = sphereMean(igi.render(256));
        const double walk = roughness > 0 ? randomWalkMean(scene, roughness, 4096) : 1.0;
        const double pieces = roughness > 0 ? piecesWalkMean(scene, path.traceable(), 2048) : 1.0;
        std::printf(
            "rough glass sphere in a sky of 1, roughness %.1f: path tracer %.5f, IGI %.5f, "
            "the BSDF's random walk %.5f, through the renderer's pieces %.5f\n",
            double(roughness), pathMean, igiMean, walk, pieces);
        EXPECT_NEAR(pathMean / pieces, 1.0, 0.015) << "roughness " << roughness;
        EXPECT_NEAR(igiMean / pieces, 1.0, 0.015) << "roughness " << roughness;
        EXPECT_EQ(path.nonFiniteValues() + igi.nonFiniteValues(), 0u);
        EXPECT_LE(pathMean, 1.0 + 2e-3) << "roughness " << roughness;
        const double tolerance = roughness <= 0.6f ? 0.01 : 0.02;
        EXPECT_NEAR(pathMean / walk, 1.0, tolerance) << "roughness " << roughness;
        EXPECT_NEAR(igiMean / walk, 1.0, tolerance) << "roughness " << roughness;
        EXPECT_NEAR(igiMean / pathMean, 1.0, 0.01) << "roughness " << roughness;
        EXPECT_LT(pathMean, previous + 2e-3) << "roughness " << roughness;
        if (roughness <= 0.2f) {
            EXPECT_NEAR(pathMean, 1.0, roughness > 0 ? 0.01 : 2e-3);
        }
        previous = pathMean;
    }
}

// The sum of an image's values (its light, every pixel).
double imageSum(const Image& image) {
    double sum = 0;
    for (const glm::vec3& v : image.pixels) sum += double(v.x + v.y + v.z);
    return sum;
}

// Point lights reach the eye through and off rough glass only by light samples taken at the
// glass: no direction sampled from its BSDF hits a point. A rough glass sphere in the dark, lit
// by a point light beside the camera (its highlight) and one behind the sphere (its light
// through two interfaces), with nothing else to make VPLs on: IGI's eye path samples them
// where it meets the glass (the first hit and every vertex inside), and must agree with the
// path tracer. Without those samples IGI saw the sphere black.
TEST(RoughGlassConvergence, PointLightsShowThroughAndOffRoughGlass) {
    for (const float roughness : {0.5f, 0.8f}) {
        Scene scene = roughSphereInTheSky(roughness);
        scene.environment.radiance = glm::vec3(0.0f);
        scene.punctualLights.push_back(
            pointLight("front", glm::vec3(1.5f, 1.0f, 4.0f), glm::vec3(10.0f)));
        scene.punctualLights.push_back(
            pointLight("behind", glm::vec3(0.3f, -0.2f, -3.0f), glm::vec3(10.0f)));
        scene.render.integrator = IntegratorKind::Path;
        scene.render.pathSamples = 64;
        InProcessRenderer path(scene);
        const double pathSum = imageSum(path.render(64));
        scene.render.integrator = IntegratorKind::Igi;
        InProcessRenderer igi(scene);
        const double igiSum = imageSum(igi.render(1024));
        std::printf(
            "rough glass sphere %.1f lit by two point lights, the image's sum: path tracer %.4f, "
            "IGI %.4f\n",
            double(roughness), pathSum, igiSum);
        EXPECT_EQ(path.nonFiniteValues() + igi.nonFiniteValues(), 0u);
        ASSERT_GT(pathSum, 1.0) << "the lights do not reach the eye: the test shows nothing";
        EXPECT_NEAR(igiSum / pathSum, 1.0, 0.03) << "roughness " << roughness;
    }
}

Scene roughGlassCornell(float roughness) {
    Scene scene = loadSceneFile(testing::sourceDir() / "scenes/cornell/cornell.json");
    scene.image.width = 64;
    scene.image.height = 48;
    for (Material& m : scene.materials)
        if (m.name == "glass") {
            m.reflection = Reflection::Ggx;
            m.roughness = roughness;
        }
    return scene;
}

// After 256 accumulated frames the mean is within 1 % of a 4096-spp path-traced image of
// the default scene whose glass ball is rough (light through it reaches the floor as caustic
// photons and VPLs beyond it; the eye sees through it by its sampled continuation).
TEST(RoughGlassConvergence, ConvergesToThePathTracerWithARoughGlassBall) {
    for (const float roughness : {0.3f, 0.7f}) {
        const testing::IgiAndPathImages r =
            testing::renderIgiAndPath(roughGlassCornell(roughness), 256, 256, 16, 64);
        EXPECT_EQ(r.nonFinite, 0u);
        const ImageDifference d = compareImages(r.igi, r.path, 16);
        std::printf(
            "rough glass ball %.1f, 256 frames against 4096 spp: bias %+.4f, 16 x 16 block "
            "error %.4f, relMSE %.3g\n",
            double(roughness), d.meanRelativeBias, d.blockRelativeError, d.relativeMse);
        EXPECT_LT(std::abs(d.meanRelativeBias), 0.01) << "roughness " << roughness;
        EXPECT_LT(d.blockRelativeError, 0.04) << "roughness " << roughness;
    }
}

// A point light inside the rough glass ball (the room lit through the glass alone). Light
// paths carry power, which refraction does not scale; eye paths carry radiance, which leaving
// the glass multiplies by 1 / eta^2 (radianceScale). IGI's room is lit by light paths (caustic
// photons and VPLs beyond the glass) and the path tracer's by eye paths that take light
// samples at the glass, so the two agree only if both are right: without the factor the path
// tracer's room was eta^2 = 2.25 times IGI's (the image's mean -22 %, the room at 0.45),
// while the ball itself, seen by the same light sample in both, agreed.
TEST(RoughGlassConvergence, ALightInsideTheGlassLightsTheRoomAsTheEyeSeesIt) {
    Scene scene = roughGlassCornell(0.5f);
    scene.image.width = 32;
    scene.image.height = 24;
    scene.quadLights.clear();
    scene.punctualLights.clear();
    scene.punctualLights.push_back(
        pointLight("inside", glm::vec3(0.42f, 0.36f, 0.3f), glm::vec3(2.0f)));
    const testing::IgiAndPathImages r = testing::renderIgiAndPath(scene, 256, 256, 8, 64);
    EXPECT_EQ(r.nonFinite, 0u);
    const ImageDifference d = compareImages(r.igi, r.path, 8);
    std::printf(
        "a point light inside the rough glass ball, IGI 256 frames against 2048 spp: bias %+.4f, "
        "8 x 8 block error %.4f, relMSE %.3g\n",
        d.meanRelativeBias, d.blockRelativeError, d.relativeMse);
    ASSERT_GT(imageSum(r.path), 1.0) << "no light leaves the glass: the test shows nothing";
    EXPECT_LT(std::abs(d.meanRelativeBias), 0.03);
    EXPECT_LT(d.blockRelativeError, 0.1);
}

}  // namespace
}  // namespace igi
