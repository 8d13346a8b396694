// Emissive textures per texel (glTF emissiveTexture): light sampling chooses a textured
// triangle by the texture integrated over it and draws points whose radiance is the texel's
// (its estimate of the emitted power is unbiased); black parts are no lights; a quad whose left
// half is bright lights the floor under that half, shows its texels to the camera, and IGI
// converges to the path tracer on it.

#include "lights/EmissiveTexture.h"

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "lights/Lights.h"
#include "math/Color.h"
#include "math/Warp.h"
#include "testing/TestScenes.h"

namespace igi {
namespace {

using testing::InProcessRenderer;

constexpr float kBright = 4.0f;

// 4 x 1 texels along u: two bright, two black (bilinear and wrapping, so the left half of a
// quad with uvs 0..1 averages three quarters of the bright value and the right one a quarter).
Texture halfBright() {
    Texture t;
    t.path = "half bright";
    t.width = 4;
    t.height = 1;
    t.texels = {glm::vec3(1.0f), glm::vec3(1.0f), glm::vec3(0.0f), glm::vec3(0.0f)};
    t.average = glm::vec3(0.5f);
    return t;
}

// A white floor (-2, -2) .. (2, 2) at z = 0 facing +z, and 1.5 above it the emitter
// (-1, -1) .. (1, 1) facing down, uvs 0..1 with u along +x; the camera looks along +y from
// below the emitter's height, so that it sees the floor and the emitter's lit side, world +x to
// the right of the image.
Scene halfBrightScene(int width = 32, int height = 24) {
    Scene scene;
    scene.textures.push_back(halfBright());
    Material emitter = testing::diffuse(glm::vec3(0.0f));
    emitter.name = "screen";
    emitter.emission = glm::vec3(kBright);
    emitter.emissionTexture = 0;
    scene.materials = {testing::diffuse(glm::vec3(0.7f)), emitter};
    scene.meshes.push_back(testing::makeQuad({-2, -2, 0}, {4, 0, 0}, {0, 4, 0}, 0));
    Mesh screen = testing::makeQuad({-1, -1, 1.5f}, {0, 2, 0}, {2, 0, 0}, 1);  // faces -z
    screen.uvs = {{0, 0}, {0, 0}, {1, 0}, {1, 0}};                             // u along +x
    scene.meshes.push_back(screen);
    scene.camera = {{0, -3, 0.4f}, {0, 0, 0.8f}, {0, 0, 1}, 60};
    scene.image = {width, height, 0};
    scene.render.causticPhotons = 0;
    return scene;
}

struct Built {
    explicit Built(const Scene& scene)
        : geometry(device, scene), traceable(geometry), lights(traceable, scene.punctualLights) {}
    EmbreeDevice device;
    SceneGeometry geometry;
    TraceableScene traceable;
    Lights lights;
};

TEST(EmissiveTexture, MeanAndBoundOverATriangle) {
    const Texture t = halfBright();
    // The two halves of the uv square: together, the mean of the texels, whatever the filter.
    const EmissiveTexture lower(t, UvTransform{},
                                {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1)});
    const EmissiveTexture upper(t, UvTransform{},
                                {glm::vec2(0, 0), glm::vec2(1, 1), glm::vec2(0, 1)});
    EXPECT_NEAR(0.5f * (lower.mean().x + upper.mean().x), 0.5f, 2e-3f);
    EXPECT_FLOAT_EQ(lower.luminanceBound(maxTexelLuminance(t)), luminance(glm::vec3(1.0f)));
    // Inside the first bright texel's centre and the second's: bright throughout.
    const EmissiveTexture bright(t, UvTransform{},
                                 {glm::vec2(0.13f, 0), glm::vec2(0.37f, 0), glm::vec2(0.2f, 1)});
    EXPECT_NEAR(bright.mean().x, 1.0f, 1e-5f);
    // Within the black texels, one texel away from the bright ones: no light at all.
    Texture wide;
    wide.width = 16;
    wide.height = 1;
    wide.texels.assign(16, glm::vec3(0.0f));
    wide.texels[0] = glm::vec3(1.0f);
    const EmissiveTexture dark(wide, UvTransform{},
                               {glm::vec2(0.4f, 0), glm::vec2(0.6f, 0), glm::vec2(0.5f, 1)});
    EXPECT_EQ(dark.luminanceBound(1.0f), 0.0f);
    EXPECT_EQ(emittedLuminance(dark, glm::vec3(1.0f), 1.0f), 0.0f);
    EXPECT_FLOAT_EQ(maxTexelLuminance(wide), luminance(glm::vec3(1.0f)));
    // A transform moves the lookup: offset by half a period, the bright texels fall elsewhere.
    UvTransform shift;
    shift.offset = {0.5f, 0.0f};
    shift.active = true;
    const EmissiveTexture shifted(t, shift,
                                  {glm::vec2(0.13f, 0), glm::vec2(0.37f, 0), glm::vec2(0.2f, 1)});
    EXPECT_NEAR(shifted.mean().x, 0.0f, 1e-5f);
}

// Per triangle, the selection probability is its share of the power, the texture integrated;
// the sample's radiance is the texel's at the sampled point, and E[L pi / pdf] is the total
// power (the estimator is unbiased), which is pi A L times the texture's mean.
TEST(EmissiveTexture, LightSamplingDrawsThePowerOfTheTexels) {
    Scene scene = halfBrightScene();
    // Split the emitter in four strips of two triangles, each a quarter of u.
    Mesh strips;
    strips.name = "strips";
    for (int i = 0; i < 4; ++i) {
        const float x0 = -1.0f + 0.5f * float(i), u0 = 0.25f * float(i);
        const auto base = std::uint32_t(strips.positions.size());
        strips.positions.insert(
            strips.positions.end(),
            {{x0, -1, 1.5f}, {x0, 1, 1.5f}, {x0 + 0.5f, 1, 1.5f}, {x0 + 0.5f, -1, 1.5f}});
        strips.uvs.insert(strips.uvs.end(), {{u0, 0}, {u0, 1}, {u0 + 0.25f, 1}, {u0 + 0.25f, 0}});
        strips.triangles.push_back({base, base + 1, base + 2});
        strips.triangles.push_back({base, base + 2, base + 3});
    }
    strips.materialIds.assign(8, 1);
    scene.meshes[1] = strips;
    const Built b(scene);
    ASSERT_EQ(b.lights.count(), 8u);
    const double area = 4.0;
    const double expected = kPi * area * luminance(glm::vec3(kBright)) * 0.5;
    EXPECT_NEAR(b.lights.totalPower() / expected, 1.0, 2e-3);

    // Uniform numbers: each strip's share of the selections against a brute-force mean of the
    // texture over it.
    const Texture t = halfBright();
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    double estimate = 0;
    std::vector<int> chosen(4, 0);
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
        const LightSample s = b.lights.sample(uniform(rng), {uniform(rng), uniform(rng)});
        ASSERT_GT(s.pdf, 0.0f);
        estimate += kPi * luminance(s.emitted) / s.pdf;
        // The radiance is the texel's where the point is: u = (x + 1) / 2.
        const float u = 0.5f * (s.position.x + 1.0f);
        EXPECT_NEAR(s.emitted.x, kBright * t.sample({u, 0.5f}).x, 1e-3f);
        chosen[std::min(3, int(2.0f * (s.position.x + 1.0f)))]++;
    }
    std::printf("strips: power / pi A L mean %.5f, E[L pi / pdf] / power %.5f\n",
                b.lights.totalPower() / expected, estimate / n / expected);
    EXPECT_NEAR(estimate / n / expected, 1.0, 0.01);
    for (int strip = 0; strip < 4; ++strip) {
        double mean = 0;
        for (int k = 0; k < 4000; ++k)
            mean += t.sample({0.25f * (strip + (k + 0.5f) / 4000), 0.5f}).x;
        mean /= 4000;
        EXPECT_NEAR(double(chosen[strip]) / n, mean / 2.0, 0.01) << "strip " << strip;
    }
}

// The floor under the bright half is brighter; the camera sees the bright half of the emitter
// bright and the dark half dark; IGI's accumulated image converges to the path tracer's.
TEST(EmissiveTexture, HalfBrightQuadLightsTheFloorUnderItsBrightHalf) {
    const testing::IgiAndPathImages both = testing::renderIgiAndPath(halfBrightScene(), 64, 256, 4);
    EXPECT_EQ(both.nonFinite, 0u);
    const Image& image = both.igi;
    const Image& truth = both.path;

    // Rows 4..8 see the emitter's underside, rows 17..20 the floor under it.
    auto mean = [&](const Image& im, int x0, int x1, int y0, int y1) {
        double s = 0;
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) s += luminance(im.pixels[std::size_t(y) * im.width + x]);
        return s / double((x1 - x0) * (y1 - y0));
    };
    const int w = image.width, h = image.height;
    for (const Image* im : {&image, &truth}) {
        const double floorLeft = mean(*im, 4, w / 2 - 2, 17, 21);
        const double floorRight = mean(*im, w / 2 + 2, w - 4, 17, 21);
        std::printf("floor: left %.4f, right %.4f\n", floorLeft, floorRight);
        EXPECT_GT(floorLeft, 1.5 * floorRight);
        const double screenLeft = mean(*im, w / 2 - 6, w / 2 - 3, 4, 8);
        const double screenRight = mean(*im, w / 2 + 3, w / 2 + 6, 4, 8);
        std::printf("emitter seen: left %.4f, right %.4f\n", screenLeft, screenRight);
        EXPECT_GT(screenLeft, 2.0 * screenRight);
    }
    const glm::dvec3 a = testing::meanOf(image), r = testing::meanOf(truth);
    std::printf("half-bright emitter: igi %.5f, path tracer %.5f\n", a.x, r.x);
    EXPECT_NEAR(a.x / r.x, 1.0, 0.01);
    const double floorIgi = mean(image, 0, w, h / 2, h), floorPath = mean(truth, 0, w, h / 2, h);
    EXPECT_NEAR(floorIgi / floorPath, 1.0, 0.015);
}

}  // namespace
}  // namespace igi
