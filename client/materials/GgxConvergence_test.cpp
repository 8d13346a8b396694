// The converging estimator on glTF metallic-roughness (GGX) surfaces against our path tracer
// with the same BRDF code: the default scene with its mirror box a rough gold metal, its glass
// ball a smooth red dielectric, its red wall a rough metal of roughness 0.6 and its white walls
// a glossy dielectric. GGX runs through every part of the estimator there: light samples with
// MIS, VPLs that carry the GGX lobe, bounded connections and their compensation, photons from
// the VPLs, continuations.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "image/ImageCompare.h"
#include "scene/SceneLoader.h"
#include "testing/TestScenes.h"
#include "util/TestPaths.h"

namespace igi {
namespace {

Scene ggxScene() {
    Scene scene = loadSceneFile(testing::sourceDir() / "scenes/cornell/cornell.json");
    scene.image.width = 64;
    scene.image.height = 48;
    for (Material& m : scene.materials) {
        const std::string name = m.name;
        m.glass = false;
        m.reflection = Reflection::Ggx;
        m.ior = 1.5f;
        if (name == "mirror") {
            m.diffuse = {1.0f, 0.78f, 0.34f};
            m.metallic = 1.0f;
            m.roughness = 0.45f;
        } else if (name == "glass") {
            m.diffuse = {0.8f, 0.2f, 0.15f};
            m.metallic = 0.0f;
            m.roughness = 0.2f;
        } else if (name == "red") {
            m.metallic = 1.0f;
            m.roughness = 0.6f;
        } else if (name == "white") {
            m.metallic = 0.0f;
            m.roughness = 0.3f;
        } else {
            m.reflection = Reflection::None;  // green stays Lambertian
        }
    }
    return scene;
}

// After 256 accumulated frames the mean is within 0.5 % of a 4096-spp path-traced image of
// the same scene, and no value is NaN or infinite.
TEST(GgxConvergence, ConvergesToThePathTracerOnMetallicRoughnessSurfaces) {
    // 4096 paths per pixel for the reference.
    const testing::IgiAndPathImages r = testing::renderIgiAndPath(ggxScene(), 256, 256, 16, 64);
    EXPECT_EQ(r.nonFinite, 0u);
    const ImageDifference d = compareImages(r.igi, r.path, 16);
    std::printf(
        "GGX scene, 256 frames against 4096 spp: bias %+.4f, 16 x 16 block error %.4f, "
        "relMSE %.3g\n",
        d.meanRelativeBias, d.blockRelativeError, d.relativeMse);
    EXPECT_LT(std::abs(d.meanRelativeBias), 0.005);
    EXPECT_LT(d.blockRelativeError, 0.03);
}

}  // namespace
}  // namespace igi
