// The renderer at the numerical extremes: scene scales from 1e-4 to 1e4, light intensities from
// 1e-6 to 1e6 against the exposure, albedos 0 and 0.999, grazing views, 1 x 1 and very wide
// images, no VPLs and very many, no caustic photons, degenerate and duplicate triangles, tiny
// specular objects. Every test also checks every output value for NaN and infinity.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include <gtest/gtest.h>

#include "Codec.h"
#include "image/ImageCompare.h"
#include "image/ToneMap.h"
#include "integrators/IgiIntegrator.h"
#include "lighting/CausticShooter.h"
#include "lights/Lights.h"
#include "math/Color.h"
#include "math/Warp.h"
#include "scene/CameraModel.h"
#include "testing/TestScenes.h"

namespace igi {
namespace {

using testing::InProcessRenderer;

// ---- Helpers ----------------------------------------------------------------------------------

::testing::AssertionResult allFinite(const Image& image) {
    std::size_t bad = 0, first = 0;
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        if (!isFinite(image.pixels[i]) && bad++ == 0) first = i;
    if (bad == 0) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << bad << " of " << image.pixels.size() << " pixels are NaN or infinite, the first at ("
           << first % std::size_t(image.width) << ", " << first / std::size_t(image.width) << ")";
}

/// Renders `frames` frames and checks every tile value and every output pixel for NaN/inf.
Image renderChecked(const Scene& scene, int frames) {
    InProcessRenderer renderer(scene);
    Image image = renderer.render(frames);
    EXPECT_EQ(renderer.nonFiniteValues(), 0u) << "NaN or infinity in the tiles' planes";
    EXPECT_TRUE(allFinite(image));
    return image;
}

/// One frame as the master shows it before accumulation: every tile's planes through the wire
/// codec (quantization, compression) and back, then the discontinuity buffer.
Image wireFrame(InProcessRenderer& renderer, const Scene& scene, std::uint32_t frame,
                std::uint32_t accumulation = 0) {
    const RenderSettings& s = scene.render;
    const int w = scene.image.width, h = scene.image.height;
    const auto tiles = makeTiles(w, h, s.interleaveX, s.interleaveY, s.tileSize);
    FrameBuffer buffer;
    buffer.reset(w, h);
    for (std::uint32_t i = 0; i < tiles.size(); ++i) {
        proto::TileResult r =
            renderer.renderer().renderNow(renderer.pool(), frame, tiles[i], accumulation);
        r.tileId = i;
        EXPECT_EQ(testing::countNonFinite(r.channels), 0u) << "tile " << i;
        const auto encoded = proto::encodeMessage(r, frame, 0);
        const auto header = proto::decodeHeader(
            std::span<const std::uint8_t, proto::kHeaderSize>(encoded.data(), proto::kHeaderSize));
        const auto back = std::get<proto::TileResult>(
            proto::decodeMessage(header, std::span(encoded).subspan(proto::kHeaderSize)));
        buffer.scatter(tiles[i], s.interleaveX, s.interleaveY, back.channels);
    }
    Image image(w, h);
    discontinuityFilterRows(buffer,
                            {s.effectiveFilterX(), s.effectiveFilterY(), s.filterDepthThreshold,
                             s.filterNormalThreshold},
                            0, h, image.pixels);
    EXPECT_TRUE(allFinite(image));
    return image;
}

/// Inside a closed diffuse sphere of radius 1 and albedo rho, a point light of intensity 1 at
/// the centre: irradiance 1 everywhere directly, radiance rho / (pi (1 - rho)) converged.
Scene closedSphere(float albedo) {
    Scene scene;
    scene.materials.push_back(testing::diffuse(glm::vec3(albedo)));
    scene.meshes.push_back(testing::makeIcosphere(5, 1.0f, glm::vec3(0), 0));
    scene.punctualLights.push_back(pointLight("centre", glm::vec3(0), glm::vec3(1.0f)));
    scene.camera = {glm::vec3(0), glm::vec3(1, 0.2f, 0.1f), glm::vec3(0, 1, 0), 70};
    scene.image = {16, 12, 0};
    scene.render.maxLightPathLength = 64;
    scene.render.causticPhotons = 0;
    return scene;
}

/// A plane z = 0 (40 x 40, albedo 0.5) seen from (0, 0, 10) and lit by a point light of
/// intensity 100 at the camera: only direct light (the plane cannot light itself), radiance
/// 0.5 / pi * 100 * cos / r^2 with cos = 10 / r, known in closed form at every pixel.
constexpr float kPlaneAlbedo = 0.5f, kPlaneDistance = 10.0f, kPlaneIntensity = 100.0f;

Scene facingPlane(int width, int height, float fovYDeg) {
    Scene scene;
    scene.materials.push_back(testing::diffuse(glm::vec3(kPlaneAlbedo)));
    scene.meshes.push_back(
        testing::makeQuad({-20, -20, 0}, {40, 0, 0}, {0, 40, 0}, 0));  // faces +z
    const glm::vec3 eye(0, 0, kPlaneDistance);
    scene.punctualLights.push_back(pointLight("at the eye", eye, glm::vec3(kPlaneIntensity)));
    scene.camera = {eye, glm::vec3(0), glm::vec3(0, 1, 0), fovYDeg};
    scene.image = {width, height, 0};
    scene.render.causticPhotons = 0;
    return scene;
}

/// The radiance the facing plane shows along the ray through image position (px, py).
double facingPlaneRadiance(const CameraModel& camera, float px, float py) {
    const glm::vec3 d = camera.direction(px, py);
    const double r = kPlaneDistance / -double(d.z);  // distance to the plane along the ray
    return kPlaneAlbedo / kPi * kPlaneIntensity * (kPlaneDistance / r) / (r * r);
}

/// Counts pixels of `image` off the facing plane's closed form by more than `tolerance`.
int pixelsOffFacingPlane(const Scene& scene, const Image& image, double tolerance) {
    const CameraModel camera(scene.camera, scene.image.width, scene.image.height);
    int off = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const double expected = facingPlaneRadiance(camera, x + 0.5f, y + 0.5f);
            const double got = image.at(x, y).x;
            if (!(std::fabs(got / expected - 1.0) <= tolerance)) {
                if (off++ < 3)
                    ADD_FAILURE() << "pixel (" << x << ", " << y << ") of " << image.width << " x "
                                  << image.height << ": " << got << ", expected " << expected;
            }
        }
    return off;
}

// ---- Scene scale ------------------------------------------------------------------------------

const char* nameOf(IntegratorKind kind) {
    return kind == IntegratorKind::Igi ? "Igi" : "Path";
}

struct ScaleCase {
    IntegratorKind integrator;
    int frames;
    bool glossy = false;
    bool metallicRoughness = false;
};
void PrintTo(const ScaleCase& c, std::ostream* os) {
    *os << nameOf(c.integrator) << ", " << c.frames << " frames" << (c.glossy ? ", glossy" : "")
        << (c.metallicRoughness ? ", metallic-roughness" : "");
}

/// The Cornell box of testing::cornellBox with its walls and box made glossy (Ks 0.2, Ns 40;
/// the floor Ns 400): the glossy bound, the MIS pair and the compensation at every scale.
Scene glossyCornellBox(float scale) {
    Scene scene = testing::cornellBox(scale, /*glassBall=*/true);
    for (int m = 0; m < 3; ++m) {
        scene.materials[m].diffuse *= 0.75f;
        scene.materials[m].specular = glm::vec3(0.2f);
        scene.materials[m].phongExponent = 40;
        scene.materials[m].reflection = Reflection::Glossy;
    }
    Material floor = scene.materials[0];
    floor.name = "glossy floor";
    floor.phongExponent = 400;
    scene.materials.push_back(floor);
    scene.meshes[0].materialIds.assign(scene.meshes[0].materialIds.size(),
                                       std::uint32_t(scene.materials.size() - 1));
    return scene;
}

/// The same box in glTF metallic-roughness: a rough dielectric, a smooth one, a rough metal and a
/// mirror-smooth metal (roughness 0: the mirror path), at every scale.
Scene metallicRoughnessCornellBox(float scale) {
    Scene scene = testing::cornellBox(scale, /*glassBall=*/true);
    const float roughness[3] = {1.0f, 0.15f, 0.5f}, metallic[3] = {0.0f, 0.0f, 1.0f};
    for (int m = 0; m < 3; ++m) {
        scene.materials[m].reflection = Reflection::Ggx;
        scene.materials[m].roughness = roughness[m];
        scene.materials[m].metallic = metallic[m];
    }
    Material floor = scene.materials[0];
    floor.name = "smooth metal floor";
    floor.roughness = 0.0f;
    floor.metallic = 1.0f;
    scene.materials.push_back(floor);
    scene.meshes[0].materialIds.assign(scene.meshes[0].materialIds.size(),
                                       std::uint32_t(scene.materials.size() - 1));
    return scene;
}

class SceneScale : public ::testing::TestWithParam<ScaleCase> {};

// Geometry, camera and lights scaled by s (point-light intensity by s^2, area-light radiance
// unchanged) must give the same image: every epsilon, clamp and radius is relative to the scene.
TEST_P(SceneScale, ACornellBoxWithAGlassBallLooksTheSameFrom1eMinus4To1e4) {
    const ScaleCase c = GetParam();
    auto sceneAt = [&](float scale) {
        Scene scene = c.metallicRoughness ? metallicRoughnessCornellBox(scale)
                      : c.glossy          ? glossyCornellBox(scale)
                                          : testing::cornellBox(scale, true);
        scene.render.integrator = c.integrator;
        scene.render.pathSamples = 8;
        return scene;
    };
    const Image reference = renderChecked(sceneAt(1.0f), c.frames);
    ASSERT_GT(testing::meanOf(reference).x, 0.05);
    for (float scale : {1e-4f, 1e-2f, 1e2f, 1e4f}) {
        SCOPED_TRACE("scale " + std::to_string(scale));
        const Image image = renderChecked(sceneAt(scale), c.frames);
        const ImageDifference d = compareImages(image, reference, 6);
        std::printf("%s scale %g: mean bias %+.2e, block error %.2e, relative MSE %.2e\n",
                    nameOf(c.integrator), scale, d.meanRelativeBias, d.blockRelativeError,
                    d.relativeMse);
        // The sampling is the same at every scale, so only rounding separates the images.
        EXPECT_LT(std::fabs(d.meanRelativeBias), 0.005);
        EXPECT_LT(d.blockRelativeError, 0.01);
    }
}

INSTANTIATE_TEST_SUITE_P(Integrators, SceneScale,
                         ::testing::Values(ScaleCase{IntegratorKind::Igi, 4},
                                           ScaleCase{IntegratorKind::Path, 1},
                                           ScaleCase{IntegratorKind::Igi, 4, true},
                                           ScaleCase{IntegratorKind::Path, 1, true},
                                           ScaleCase{IntegratorKind::Igi, 4, false, true},
                                           ScaleCase{IntegratorKind::Path, 1, false, true}),
                         [](const auto& info) {
                             return std::string(nameOf(info.param.integrator)) +
                                    (info.param.glossy ? "Glossy" : "") +
                                    (info.param.metallicRoughness ? "MetallicRoughness" : "");
                         });

// ---- Light intensity against exposure --------------------------------------------------------

struct IntensityCase {
    bool glossy;
    std::uint32_t accumulation;  ///< 0: the first frame after a change; > 0: an accumulated one
};
void PrintTo(const IntensityCase& c, std::ostream* os) {
    *os << (c.glossy ? "glossy" : "diffuse") << ", accumulation " << c.accumulation;
}

class LightIntensity : public ::testing::TestWithParam<IntensityCase> {};

// Radiance and intensity times s, exposure -log2(s): after the wire's quantization and the
// discontinuity buffer, the 8-bit display values are those of s = 1 within one code. In an
// accumulated frame too: the roulette and the compensation decide by albedo and geometry, never
// by how bright a path is.
TEST_P(LightIntensity, From1eMinus6To1e6TheDisplayedImageMatchesWithinOneCode) {
    const IntensityCase c = GetParam();
    auto sceneWith = [&](float s) {
        Scene scene = c.glossy ? glossyCornellBox(1.0f) : testing::cornellBox(1.0f, true);
        scene.quadLights[0].radiance *= s;
        scene.punctualLights[0].intensity *= s;
        return scene;
    };
    const Scene base = sceneWith(1.0f);
    InProcessRenderer baseRenderer(base);
    const Image reference = wireFrame(baseRenderer, base, 0, c.accumulation);
    int midtones = 0;
    for (const auto& p : reference.pixels) {
        const int code = toneMapChannel(p.y, 1.0f);
        midtones += code > 20 && code < 235;
    }
    ASSERT_GT(midtones, int(reference.pixels.size()) / 2)
        << "the reference must be mostly midtones";
    for (float s : {1e-6f, 1e-3f, 1e3f, 1e6f}) {
        SCOPED_TRACE("intensity x " + std::to_string(s));
        const Scene scene = sceneWith(s);
        InProcessRenderer renderer(scene);
        const Image image = wireFrame(renderer, scene, 0, c.accumulation);
        const float exposureScale = std::exp2(-std::log2(s));
        int worst = 0;
        for (std::size_t i = 0; i < image.pixels.size(); ++i)
            for (int c = 0; c < 3; ++c)
                worst = std::max(worst,
                                 std::abs(int(toneMapChannel(image.pixels[i][c], exposureScale)) -
                                          int(toneMapChannel(reference.pixels[i][c], 1.0f))));
        std::printf("intensity x %g: largest 8-bit difference %d\n", s, worst);
        EXPECT_LE(worst, 1);
    }
}

INSTANTIATE_TEST_SUITE_P(Materials, LightIntensity,
                         ::testing::Values(IntensityCase{false, 0}, IntensityCase{true, 0},
                                           IntensityCase{true, 2}),
                         [](const auto& info) {
                             return std::string(info.param.glossy ? "Glossy" : "Diffuse") +
                                    "Accumulation" + std::to_string(info.param.accumulation);
                         });

// ---- Albedo 0 and 0.999 -----------------------------------------------------------------------

// Albedo 0.999 in a closed sphere, with the paper's walk: its paths end when the quasi-random
// roulette has none left, so the image converges to the sum of the bounces the walk reaches,
// finite and below the analytic rho I / (pi R^2 (1 - rho)) of all bounces.
TEST(Albedo, NearOneStaysFiniteAndBelowTheClosedSphereBound) {
    const float rho = 0.999f;
    Scene scene = closedSphere(rho);
    scene.render.roulette = false;
    InProcessRenderer renderer(scene);
    const Image image = renderer.render(4);
    EXPECT_EQ(renderer.nonFiniteValues(), 0u);
    ASSERT_TRUE(allFinite(image));
    const LightingSetBuilder& builder = renderer.renderer().builder();
    int deepest = 0;  // deepest light-path vertex that holds VPLs
    for (int v = 1; v < 64; ++v)
        if (builder.survivors(std::uint32_t(v - 1)) > 0) deepest = v;
    double bounces = 0;
    for (int v = 0; v <= deepest; ++v) bounces += std::pow(double(rho), v);
    const double expected = rho / kPi * bounces;
    const double bound = rho / (kPi * (1.0 - rho));
    const double mean = testing::meanOf(image).x;
    std::printf("albedo 0.999: %d light-path vertices, mean %.4g, expected %.4g, bound %.4g\n",
                deepest, mean, expected, bound);
    EXPECT_GE(deepest, 3);
    EXPECT_NEAR(mean / expected, 1.0, 0.02);
    for (const auto& p : image.pixels) ASSERT_LT(p.x, bound) << "energy exploded";
}

// The same with Russian roulette, which every frame has (an accumulated one here): the walk's
// paths go on, each surviving a bounce with probability 0.999, so
// nearly every path reaches the safety cap, and the image is the series truncated there,
// finite and below the bound.
TEST(Albedo, NearOneWithRouletteIsTheSeriesUpToTheCap) {
    const float rho = 0.999f;
    Scene scene = closedSphere(rho);
    scene.render.roulette = true;
    scene.render.maxLightPathLength = 4;
    scene.render.rouletteMaxLength = 24;
    InProcessRenderer renderer(scene);
    const Image image = renderer.render(4, 0, /*firstAccumulation=*/1);
    EXPECT_EQ(renderer.nonFiniteValues(), 0u);
    ASSERT_TRUE(allFinite(image));
    double bounces = 0;  // vertices 0 (direct) .. cap - 1
    for (int v = 0; v < scene.render.rouletteMaxLength; ++v) bounces += std::pow(double(rho), v);
    const double expected = rho / kPi * bounces;
    const double mean = testing::meanOf(image).x;
    std::printf("albedo 0.999 with roulette: mean %.4g, expected %.4g\n", mean, expected);
    EXPECT_NEAR(mean / expected, 1.0, 0.02);
    for (const auto& p : image.pixels) ASSERT_LT(p.x, rho / (kPi * (1.0 - rho)));
}

// Kd + Ks = 0.999 with a Phong lobe (Ns 40), in accumulated frames: the glossy bound, the
// MIS pair, the compensation's recursion and the roulette through glossy vertices must keep
// every pixel finite and below the diffuse sphere's bound (a normalized Phong lobe loses the
// part of its cone below the horizon, so it reflects at most as much as Kd + Ks would), and
// above the direct light alone.
TEST(Albedo, NearOneGlossyStaysFiniteAndBounded) {
    const float rho = 0.999f;
    Scene scene = closedSphere(rho);
    scene.materials[0].diffuse = glm::vec3(0.799f);
    scene.materials[0].specular = glm::vec3(0.2f);
    scene.materials[0].phongExponent = 40;
    scene.materials[0].reflection = Reflection::Glossy;
    scene.render.rouletteMaxLength = 24;
    InProcessRenderer renderer(scene);
    const Image image = renderer.render(4, 0, /*firstAccumulation=*/1);
    EXPECT_EQ(renderer.nonFiniteValues(), 0u);
    ASSERT_TRUE(allFinite(image));
    const double mean = testing::meanOf(image).x;
    std::printf("glossy albedo 0.999: mean %.4g, direct alone %.4g\n", mean, 0.799 / kPi);
    EXPECT_GT(mean, 2 * 0.799 / kPi) << "the bounces are missing";
    for (const auto& p : image.pixels) ASSERT_LT(p.x, rho / (kPi * (1.0 - rho)));
}

// The path tracer at albedo 0.999: Russian roulette keeps the throughput bounded, and the
// paths' next-event estimates at vertices 0 .. maxPathLength - 1 sum to the truncated series.
TEST(Albedo, NearOneInThePathTracerIsTheTruncatedSeries) {
    const float rho = 0.999f;
    Scene scene = closedSphere(rho);
    scene.render.integrator = IntegratorKind::Path;
    scene.render.pathSamples = 16;
    scene.render.maxPathLength = 16;
    const Image image = renderChecked(scene, 2);
    double bounces = 0;
    for (int d = 0; d < scene.render.maxPathLength; ++d) bounces += std::pow(double(rho), d);
    const double expected = rho / kPi * bounces;
    const double mean = testing::meanOf(image).x;
    std::printf("path tracer, albedo 0.999: mean %.4g, expected %.4g\n", mean, expected);
    EXPECT_NEAR(mean / expected, 1.0, 0.02);
    for (const auto& p : image.pixels) ASSERT_LT(p.x, rho / (kPi * (1.0 - rho)));
}

// Albedo 0 everywhere: nothing is reflected, so every pixel is exactly black, no VPL is stored,
// and the irradiance at any wall point is the direct light alone, exactly I / R^2.
TEST(Albedo, ZeroGivesABlackImageAndExactlyTheDirectIrradiance) {
    const Scene scene = closedSphere(0.0f);
    InProcessRenderer renderer(scene);
    const Image image = renderer.render(1);
    EXPECT_EQ(renderer.nonFiniteValues(), 0u);
    for (const auto& p : image.pixels) ASSERT_EQ(p, glm::vec3(0.0f));
    const LightingSet set = renderer.renderer().builder().build(0, 0);
    EXPECT_TRUE(set.indirect.empty());
    const CameraModel camera(scene.camera, scene.image.width, scene.image.height);
    const IgiIntegrator igi(renderer.traceable(), renderer.renderer().lights(), scene.render,
                            camera);
    const Mesh& sphere = scene.meshes[0];
    for (std::size_t i = 0; i < sphere.positions.size(); i += 97) {
        const glm::vec3 inward = -sphere.normals[i];
        RayCounters counters;
        const glm::vec3 e =
            igi.irradianceOverPi(sphere.positions[i], inward, inward, set, counters);
        ASSERT_NEAR(e.x * kPi, 1.0, 0.01) << "vertex " << i;
    }
}

// Only the floor reflects (albedo 0.75), every other surface is black: the floor's VPLs can
// light nothing that reflects, so the full IGI image is the direct-light image, bit for bit.
TEST(Albedo, ZeroEverywhereButTheFloorLeavesOnlyDirectLight) {
    Scene scene = testing::cornellBox(1.0f);
    for (Material& m : scene.materials) m.diffuse = glm::vec3(0.0f);
    scene.materials.push_back(testing::diffuse(glm::vec3(0.75f)));
    scene.meshes[0].materialIds.assign(scene.meshes[0].materialIds.size(), 4);  // the floor
    const Image full = renderChecked(scene, 2);
    scene.render.maxLightPathLength = 1;
    const Image direct = renderChecked(scene, 2);
    ASSERT_GT(testing::meanOf(direct).x, 0.01);
    for (std::size_t i = 0; i < full.pixels.size(); ++i)
        ASSERT_EQ(full.pixels[i], direct.pixels[i]);
}

// ---- Grazing views ----------------------------------------------------------------------------

struct GrazingCase {
    IntegratorKind integrator;
    float eyeHeight;  ///< above the floor, which is 1000 wide, under a light 100 high
};
void PrintTo(const GrazingCase& c, std::ostream* os) {
    *os << nameOf(c.integrator) << ", eye at " << c.eyeHeight;
}

class GrazingView : public ::testing::TestWithParam<GrazingCase> {};

// A camera a hair above a large floor looks along it, at the floor 30 units away, with a field of
// view a fifth of its angle to the floor: the floor is seen at angles down to h / 36 rad (6e-8
// rad for h = 1e-6). A point light 100 above the eye lights it directly (nothing else can), so
// every pixel whose footprint is small has a known radiance.
TEST_P(GrazingView, AFloorSeenEdgeOnHasItsAnalyticRadiance) {
    const GrazingCase c = GetParam();
    constexpr float kLightHeight = 100.0f, kIntensity = 1e4f, kAlbedo = 0.5f, kHalf = 500.0f;
    Scene scene;
    scene.materials.push_back(testing::diffuse(glm::vec3(kAlbedo)));
    scene.meshes.push_back(testing::makeQuad({-kHalf, 0, -kHalf}, {0, 0, 2 * kHalf},
                                             {2 * kHalf, 0, 0}, 0));  // faces +y
    scene.punctualLights.push_back(
        pointLight("above", {0, kLightHeight, 0}, glm::vec3(kIntensity)));
    const glm::vec3 eye(0, c.eyeHeight, 0);
    const double angle = c.eyeHeight / 30.0;  // of the view's centre below the horizon
    const float fov = float(2.0 * std::atan(angle / 10.0) * 180.0 / 3.14159265358979);
    scene.camera = {eye, eye + glm::vec3(1.0f, float(-std::tan(angle)), 0.0f), glm::vec3(0, 1, 0),
                    fov};
    scene.image = {48, 32, 0};
    scene.render.integrator = c.integrator;
    scene.render.pathSamples = 2;
    scene.render.causticPhotons = 0;
    const Image image = renderChecked(scene, 2);

    const CameraModel camera(scene.camera, scene.image.width, scene.image.height);
    auto floorRadiance = [&](float px, float py, bool& onFloor) {
        const glm::dvec3 d(camera.direction(px, py));
        onFloor = d.y < 0;
        if (!onFloor) return 0.0;
        const glm::dvec3 p = glm::dvec3(eye) + (-double(eye.y) / d.y) * d;
        onFloor = std::max(std::fabs(p.x), std::fabs(p.z)) < 0.9 * kHalf;
        const double r2 = p.x * p.x + p.z * p.z + double(kLightHeight) * kLightHeight;
        return kAlbedo / kPi * kIntensity * kLightHeight / (r2 * std::sqrt(r2));
    };
    int checked = 0, off = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            bool top = false, bottom = false, centre = false;
            const double a = floorRadiance(x + 0.5f, float(y) - 1.0f, top);
            const double b = floorRadiance(x + 0.5f, float(y) + 2.0f, bottom);
            const double expected = floorRadiance(x + 0.5f, y + 0.5f, centre);
            // Only pixels whose filter window lies on the floor where the radiance is smooth.
            if (!(top && bottom && centre) || std::fabs(a / b - 1.0) > 0.01) continue;
            ++checked;
            const double got = image.at(x, y).x;
            if (!(std::fabs(got / expected - 1.0) < 0.02) && off++ < 3)
                ADD_FAILURE() << "pixel (" << x << ", " << y << "): " << got << ", expected "
                              << expected;
        }
    std::printf("grazing view from %g: %d pixels checked, %d off\n", c.eyeHeight, checked, off);
    EXPECT_GT(checked, image.width * image.height / 4);
    EXPECT_EQ(off, 0);
}

INSTANTIATE_TEST_SUITE_P(Heights, GrazingView,
                         ::testing::Values(GrazingCase{IntegratorKind::Igi, 1e-1f},
                                           GrazingCase{IntegratorKind::Igi, 1e-3f},
                                           GrazingCase{IntegratorKind::Igi, 1e-6f},
                                           GrazingCase{IntegratorKind::Path, 1e-3f}),
                         [](const auto& info) {
                             return std::string(nameOf(info.param.integrator)) + "_eye_at_1e" +
                                    std::to_string(
                                        int(std::lround(std::log10(info.param.eyeHeight))))
                                        .replace(0, 1, "m");
                         });

// ---- Image sizes ------------------------------------------------------------------------------

struct SizeCase {
    int width, height;
    float fovYDeg;
    IntegratorKind integrator;
};
void PrintTo(const SizeCase& c, std::ostream* os) {
    *os << c.width << " x " << c.height << ", " << nameOf(c.integrator);
}

class ImageSize : public ::testing::TestWithParam<SizeCase> {};

// Tiny and extremely wide or tall images: the tiles cover every pixel, the camera maps pixels
// to the right rays, the filter's window stays inside the image; every pixel of a plane lit
// from the eye has its closed-form radiance.
TEST_P(ImageSize, EveryPixelOfALitPlaneHasItsClosedFormRadiance) {
    const SizeCase c = GetParam();
    Scene scene = facingPlane(c.width, c.height, c.fovYDeg);
    scene.render.integrator = c.integrator;
    scene.render.pathSamples = 1;
    scene.render.directSamples = 1;
    const Image image = renderChecked(scene, 1);
    EXPECT_EQ(pixelsOffFacingPlane(scene, image, 0.005), 0);
}

INSTANTIATE_TEST_SUITE_P(Sizes, ImageSize,
                         ::testing::Values(SizeCase{1, 1, 1.0f, IntegratorKind::Igi},
                                           SizeCase{1, 1, 1.0f, IntegratorKind::Path},
                                           SizeCase{1, 7, 2.0f, IntegratorKind::Igi},
                                           SizeCase{7, 1, 1.0f, IntegratorKind::Igi},
                                           SizeCase{2, 2, 1.0f, IntegratorKind::Igi},
                                           SizeCase{16384, 16, 0.1f, IntegratorKind::Igi},
                                           SizeCase{16, 16384, 80.0f, IntegratorKind::Igi}),
                         [](const auto& info) {
                             return std::to_string(info.param.width) + "x" +
                                    std::to_string(info.param.height) +
                                    (info.param.integrator == IntegratorKind::Igi ? "_Igi"
                                                                                  : "_Path");
                         });

// The tile layout of the largest images a scene file allows covers every pixel exactly once.
TEST(ImageSize, TilesPartitionTheLargestImages) {
    for (auto [w, h] : {std::pair{4096, 3072}, std::pair{16381, 1021}, std::pair{16384, 1},
                        std::pair{1, 16384}}) {
        std::vector<std::uint8_t> covered(std::size_t(w) * h, 0);
        for (const Tile& t : makeTiles(w, h, 3, 3, 32))
            for (int i = 0; i < t.pixelCount(3, 3); ++i)
                ++covered[std::size_t(t.pixelY(i, 3, 3)) * w + t.pixelX(i, 3)];
        EXPECT_EQ(std::count(covered.begin(), covered.end(), 1), std::ptrdiff_t(covered.size()))
            << w << " x " << h;
    }
}

// ---- VPL counts -------------------------------------------------------------------------------

// No VPLs at all (no indirect samples, light paths of the light vertex only): the direct image,
// whatever other setting would have asked for VPLs.
TEST(VplCount, ZeroVplsGiveTheDirectImage) {
    Scene scene = testing::cornellBox(1.0f, /*glassBall=*/true);
    scene.render.roulette = false;  // maxLightPathLength cuts the paths
    const Image full = renderChecked(scene, 1);
    scene.render.indirectVpls = 0;
    scene.render.maxLightPathLength = 1;
    InProcessRenderer renderer(scene);
    const Image none = renderer.render(1);
    EXPECT_TRUE(allFinite(none));
    EXPECT_EQ(renderer.nonFiniteValues(), 0u);
    EXPECT_EQ(renderer.renderer().builder().vplPaths(), 0u);
    EXPECT_TRUE(renderer.renderer().builder().build(0, 0).indirect.empty());
    scene.render.maxLightPathLength = 4;  // paths may be long, but none is asked for
    const Image noneLong = renderChecked(scene, 1);
    scene.render.indirectVpls = 18;
    scene.render.maxLightPathLength = 1;  // VPLs asked for, but paths end on the light
    const Image noneShort = renderChecked(scene, 1);
    for (std::size_t i = 0; i < none.pixels.size(); ++i) {
        ASSERT_EQ(none.pixels[i], noneLong.pixels[i]);
        ASSERT_EQ(none.pixels[i], noneShort.pixels[i]);
    }
    EXPECT_LT(testing::meanOf(none).x, 0.9 * testing::meanOf(full).x) << "VPLs add light";
    scene.render.maxLightPathLength = 4;
    scene.render.directSamples = 0;  // and the other way round: VPLs without direct samples
    EXPECT_GT(testing::meanOf(renderChecked(scene, 1)).x, 0.0);
}

// 20,000 VPLs per set: one frame in a closed sphere is the analytic answer.
TEST(VplCount, TwentyThousandPerSetGiveTheClosedSphereRadianceInOneFrame) {
    Scene scene = closedSphere(0.5f);
    scene.render.indirectVpls = 20000;
    scene.image = {6, 6, 0};
    InProcessRenderer renderer(scene);
    const Image image = renderer.render(1);
    EXPECT_EQ(renderer.nonFiniteValues(), 0u);
    ASSERT_TRUE(allFinite(image));
    const LightingSet set = renderer.renderer().builder().build(0, 4);
    std::printf("%zu VPLs from %u light paths\n", set.indirect.size(), set.lightPaths);
    // A few walks end early where a cosine-distributed direction about the interpolated normal
    // points into the faceted sphere.
    EXPECT_GE(set.indirect.size(), 19900u);
    const double expected = 0.5 / (kPi * 0.5);
    for (const auto& p : image.pixels) ASSERT_NEAR(p.x / expected, 1.0, 0.02);
}

// ---- Caustics ---------------------------------------------------------------------------------

// A glass ball with no caustic photons: finite, and darker than with photons exactly where the
// photons land (they only ever add light).
TEST(CausticPhotons, ZeroWithAGlassBallOnlyRemovesTheCaustic) {
    Scene scene = testing::cornellBox(1.0f, /*glassBall=*/true);
    const Image with = renderChecked(scene, 1);
    scene.render.causticPhotons = 0;
    InProcessRenderer renderer(scene);
    const Image without = renderer.render(1);
    EXPECT_EQ(renderer.nonFiniteValues(), 0u);
    EXPECT_TRUE(allFinite(without));
    EXPECT_FALSE(renderer.renderer().builder().causticsActive());
    int darker = 0;
    for (std::size_t i = 0; i < with.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            ASSERT_LE(without.pixels[i][c], with.pixels[i][c] * (1 + 1e-6f));
            darker += without.pixels[i][c] < with.pixels[i][c] * (1 - 1e-3f);
        }
    EXPECT_GT(darker, 0) << "the ball's caustic must be visible with photons";
}

class TinyMirror : public ::testing::TestWithParam<float> {};

// A square mirror of side a at distance 1 from a point light, facing it, in a large diffuse
// room: the photons it reflects must carry reflectance * I * (its solid angle), however small
// it looks from the light (photons are aimed at a cone around it).
TEST_P(TinyMirror, ReflectsThePowerItsSolidAngleReceives) {
    const float a = GetParam();
    constexpr float kReflectance = 0.9f;
    Scene scene;
    scene.materials.push_back(testing::diffuse(glm::vec3(0.5f)));
    Material mirror;
    mirror.name = "mirror";
    mirror.diffuse = glm::vec3(0.0f);
    mirror.specular = glm::vec3(kReflectance);
    mirror.reflection = Reflection::Mirror;
    scene.materials.push_back(mirror);
    // The room: a box of side 20 about the origin, seen from inside (faces wound inward).
    Mesh room = testing::makeBox(glm::vec3(0), glm::vec3(10), 0, 0);
    for (auto& t : room.triangles) std::swap(t.y, t.z);
    scene.meshes.push_back(room);
    // The mirror in the plane x = 1, facing -x (toward the light at the origin).
    scene.meshes.push_back(testing::makeQuad({1, -a / 2, -a / 2}, {0, 0, a}, {0, a, 0}, 1));
    scene.punctualLights.push_back(pointLight("light", glm::vec3(0), glm::vec3(1.0f)));
    scene.render.causticPhotons = 20000;
    EmbreeDevice device;
    SceneGeometry geometry(device, scene);
    TraceableScene traceable(geometry);
    Lights lights(traceable, scene.punctualLights);
    CausticShooter shooter(traceable, lights, scene.render);
    ASSERT_TRUE(shooter.active());
    double power = 0;
    std::size_t bad = 0;
    constexpr int kSets = 2;
    for (std::uint32_t k = 0; k < kSets; ++k) {
        std::uint32_t shot = 0;
        RayCounters counters;
        for (const CausticPhoton& p : shooter.shoot(0, k, shot, counters)) {
            bad += isFinite(p.power) && isFinite(p.position) ? 0 : 1;
            power += p.power.x;
        }
    }
    power /= kSets;
    // Solid angle of an a x a square at distance 1 on its axis.
    const double omega = 4.0 * std::asin(double(a) * a / (double(a) * a + 4.0));
    const double expected = kReflectance * omega;
    std::printf("mirror of side %g: caustic power / expected %.4f\n", a, power / expected);
    EXPECT_EQ(bad, 0u);
    EXPECT_NEAR(power / expected, 1.0, 0.01);
}

INSTANTIATE_TEST_SUITE_P(Sides, TinyMirror, ::testing::Values(1e-1f, 1e-2f, 1e-3f, 1e-4f));

// ---- Degenerate and duplicate triangles -------------------------------------------------------

/// Adds to a Cornell box (inside its bounds, so its size is unchanged) triangles of zero area:
/// repeated indices and collinear vertices in the box's mesh, a mesh of nothing else, and an
/// emissive triangle of zero area, which no light may be made of.
Scene withDegenerateTriangles(Scene scene, float s) {
    Mesh& box = scene.meshes[5];
    const auto n = std::uint32_t(box.positions.size());
    const glm::vec3 p0 = box.positions[0], p1 = box.positions[1];
    box.positions.push_back(0.5f * (p0 + p1));  // on the edge p0 p1: collinear with it
    box.triangles.insert(box.triangles.end(), {{0, 0, 1}, {3, 3, 3}, {0, n, 1}, {n, 1, 0}});
    box.materialIds.resize(box.triangles.size(), 0);

    Mesh line;
    line.name = "degenerate only";
    for (int i = 0; i < 5; ++i)
        line.positions.push_back(s * glm::vec3(0.2f + 0.1f * i, 0.5f, 0.5f));
    line.triangles = {{0, 1, 2}, {1, 3, 4}, {2, 2, 2}, {4, 0, 0}, {0, 4, 2}};
    line.materialIds.assign(line.triangles.size(), 0);
    scene.meshes.push_back(line);

    Material hot = testing::diffuse(glm::vec3(0.5f));
    hot.name = "hot";
    hot.emission = glm::vec3(100.0f);
    scene.materials.push_back(hot);
    Mesh emitter;
    emitter.name = "emissive degenerate";
    emitter.positions = {s * glm::vec3(0.4f, 0.9f, 0.4f), s * glm::vec3(0.5f, 0.9f, 0.5f),
                         s * glm::vec3(0.6f, 0.9f, 0.6f)};
    emitter.triangles = {{0, 1, 2}, {0, 0, 1}, {2, 1, 0}};
    emitter.materialIds.assign(3, std::uint32_t(scene.materials.size() - 1));
    scene.meshes.push_back(emitter);
    return scene;
}

class DegenerateTriangles : public ::testing::TestWithParam<IntegratorKind> {};

// Zero-area triangles are invisible and emit nothing: the image is that of the scene without
// them, and the lights are the same.
TEST_P(DegenerateTriangles, ChangeNothing) {
    Scene base = testing::cornellBox(1.0f, /*glassBall=*/true);
    base.render.integrator = GetParam();
    base.render.pathSamples = 8;
    const Scene degenerate = withDegenerateTriangles(base, 1.0f);
    const Image reference = renderChecked(base, 2);
    const Image image = renderChecked(degenerate, 2);
    const ImageDifference d = compareImages(image, reference, 6);
    std::printf("degenerate triangles: mean bias %+.2e, block error %.2e\n", d.meanRelativeBias,
                d.blockRelativeError);
    EXPECT_LT(std::fabs(d.meanRelativeBias), 0.002);
    EXPECT_LT(d.blockRelativeError, 0.005);

    EmbreeDevice device;
    SceneGeometry g0(device, base), g1(device, degenerate);
    TraceableScene t0(g0), t1(g1);
    const Lights l0(t0, base.punctualLights), l1(t1, degenerate.punctualLights);
    EXPECT_EQ(l1.count(), l0.count()) << "an emissive triangle of zero area became a light";
    EXPECT_DOUBLE_EQ(l1.totalPower(), l0.totalPower());
    EXPECT_FLOAT_EQ(t1.diagonal(), t0.diagonal());
}

INSTANTIATE_TEST_SUITE_P(Integrators, DegenerateTriangles,
                         ::testing::Values(IntegratorKind::Igi, IntegratorKind::Path),
                         [](const auto& info) { return nameOf(info.param); });

// A scene of nothing but degenerate triangles, some emissive: no light, no hit, a black image.
TEST(DegenerateTriangles, ASceneOfOnlyDegenerateTrianglesIsBlack) {
    for (IntegratorKind kind : {IntegratorKind::Igi, IntegratorKind::Path}) {
        Scene scene;
        Material hot = testing::diffuse(glm::vec3(0.5f));
        hot.emission = glm::vec3(1.0f);
        scene.materials = {testing::diffuse(glm::vec3(0.5f)), hot};
        Mesh point;  // every vertex at one point: bounds of zero size
        point.positions.assign(3, glm::vec3(1, 2, 3));
        point.triangles = {{0, 1, 2}, {0, 0, 0}};
        point.materialIds = {0, 1};
        Mesh line;
        line.positions = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
        line.triangles = {{0, 1, 2}, {2, 1, 0}};
        line.materialIds = {1, 0};
        scene.meshes = {point, line};
        scene.camera = {glm::vec3(1, 1, 5), glm::vec3(1, 1, 1), glm::vec3(0, 1, 0), 60};
        scene.image = {8, 6, 0};
        scene.render.integrator = kind;
        scene.render.pathSamples = 1;
        const Image image = renderChecked(scene, 1);
        for (const auto& p : image.pixels) ASSERT_EQ(p, glm::vec3(0.0f));
    }
}

/// The mesh with every triangle twice.
Mesh doubled(Mesh mesh) {
    const std::size_t n = mesh.triangles.size();
    for (std::size_t i = 0; i < n; ++i) {
        mesh.triangles.push_back(mesh.triangles[i]);
        mesh.materialIds.push_back(mesh.materialIds[i]);
    }
    return mesh;
}

class DuplicateTriangles : public ::testing::TestWithParam<IntegratorKind> {};

// Every face of the room, the box and the ball twice (same material, same place): the same
// surfaces, the same image.
TEST_P(DuplicateTriangles, OfDiffuseAndGlassSurfacesChangeNothing) {
    Scene base = testing::cornellBox(1.0f, /*glassBall=*/true);
    base.render.integrator = GetParam();
    base.render.pathSamples = 8;
    Scene twice = base;
    for (Mesh& m : twice.meshes) m = doubled(m);
    const ImageDifference d = compareImages(renderChecked(twice, 2), renderChecked(base, 2), 6);
    std::printf("duplicated faces: mean bias %+.2e, block error %.2e\n", d.meanRelativeBias,
                d.blockRelativeError);
    EXPECT_LT(std::fabs(d.meanRelativeBias), 0.002);
    EXPECT_LT(d.blockRelativeError, 0.005);
}

// The ceiling light as an emissive mesh, every triangle twice: still one light of the same
// power (a surface seen once must not be sampled twice).
TEST_P(DuplicateTriangles, OfAnEmitterDoNotDoubleItsLight) {
    Scene base = testing::cornellBox(1.0f);
    base.render.integrator = GetParam();
    base.render.pathSamples = 8;
    const QuadLight q = base.quadLights[0];
    base.quadLights.clear();
    Material panel;
    panel.name = "panel";
    panel.diffuse = glm::vec3(0.0f);
    panel.emission = q.radiance;
    base.materials.push_back(panel);
    base.meshes.push_back(
        testing::makeQuad(q.corner, q.edge1, q.edge2, std::uint32_t(base.materials.size() - 1)));
    Scene twice = base;
    twice.meshes.back() = doubled(twice.meshes.back());
    const ImageDifference d = compareImages(renderChecked(twice, 2), renderChecked(base, 2), 6);
    std::printf("duplicated emitter: mean bias %+.2e, block error %.2e\n", d.meanRelativeBias,
                d.blockRelativeError);
    EXPECT_LT(std::fabs(d.meanRelativeBias), 0.002);
    EXPECT_LT(d.blockRelativeError, 0.005);
}

INSTANTIATE_TEST_SUITE_P(Integrators, DuplicateTriangles,
                         ::testing::Values(IntegratorKind::Igi, IntegratorKind::Path),
                         [](const auto& info) { return nameOf(info.param); });

}  // namespace
}  // namespace igi
