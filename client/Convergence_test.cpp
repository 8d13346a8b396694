// The converging estimator against a cached path-traced reference of the project's default
// scene (Cornell room, mirror box, glass ball: every part of the estimator is used, the
// roulette, the compensation, the VPLs' photons, the progressive radius and filter).
// The reference is client/testdata/default-64x48-reference.exr, 65536 paths per pixel, made by
// scripts/make_bias_reference.sh; if the default scene changes, run that script again.
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <gtest/gtest.h>

#include "image/ImageCompare.h"
#include "image/ImageIO.h"
#include "scene/SceneLoader.h"
#include "testing/TestScenes.h"
#include "util/TestPaths.h"

namespace igi {
namespace {

struct Measured {
    double bias = 0;
    double blockError = 0;
};

Measured accumulated(bool converge, int frames, const Image& reference) {
    Scene scene = loadSceneFile(testing::sourceDir() / "scenes/cornell/cornell.json");
    scene.image.width = reference.width;
    scene.image.height = reference.height;
    if (!converge) {
        scene.render.roulette = false;
        scene.render.clampCompensation = ClampCompensation::Off;
        scene.render.indirectCausticPhotons = 0;
        scene.render.progressiveRadius = false;
        scene.render.progressiveFilter = false;
    }
    testing::InProcessRenderer renderer(scene);
    const Image image = renderer.render(frames);
    EXPECT_EQ(renderer.nonFiniteValues(), 0u);
    const ImageDifference d = compareImages(image, reference, 16);
    std::printf("%s, %d frames: bias %+.4f, 16 x 16 block error %.4f, relMSE %.3g\n",
                converge ? "converging" : "the paper's estimator", frames, d.meanRelativeBias,
                d.blockRelativeError, d.relativeMse);
    return {d.meanRelativeBias, d.blockRelativeError};
}

// After 256 accumulated frames the image's mean is within 0.5 % of the reference's (measured
// -0.02 %) and its 16 x 16 blocks within 2 % on average (measured 0.4 %), where the paper's
// estimator stays several per cent dark (light paths cut at 4 vertices, the clamp's energy lost, no
// light through the mirror and glass from the walls).
TEST(Convergence, DefaultSceneConvergesToThePathTracedReference) {
    const auto file = testing::sourceDir() / "client/testdata/default-64x48-reference.exr";
    ASSERT_TRUE(std::filesystem::exists(file)) << file << ": run scripts/make_bias_reference.sh";
    const Image reference = readImage(file);
    const Measured converging = accumulated(true, 256, reference);
    EXPECT_LT(std::abs(converging.bias), 0.005)
        << "if the default scene changed, regenerate the reference with "
           "scripts/make_bias_reference.sh";
    EXPECT_LT(converging.blockError, 0.02);
    const Measured paper = accumulated(false, 256, reference);
    EXPECT_LT(paper.bias, -0.03) << "the test would not see the bias it is there to catch";
}

}  // namespace
}  // namespace igi
