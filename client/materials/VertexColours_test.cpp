// glTF COLOR_0 multiplies the base colour (baseColorFactor x baseColorTexture x COLOR_0): a
// floor whose vertices are all one colour renders as a floor of that base colour, and colours
// that differ between vertices are interpolated across the triangles.

#include <cstdio>

#include <gtest/gtest.h>

#include "testing/TestScenes.h"

namespace igi {
namespace {

// A floor (-1, -1) .. (1, 1) at z = 0 facing +z, seen from above, under a point light.
Scene floorScene(glm::vec3 baseColour) {
    Scene scene;
    scene.materials = {testing::diffuse(baseColour)};
    scene.meshes.push_back(testing::makeQuad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 0));
    scene.punctualLights.push_back(pointLight("light", {0.2f, 0.1f, 1.5f}, glm::vec3(2.0f)));
    scene.camera = {{0, 0, 3}, {0, 0, 0}, {0, 1, 0}, 40};
    scene.image = {24, 24, 0};
    scene.render.causticPhotons = 0;
    return scene;
}

TEST(VertexColours, OneColourRendersAsThatBaseColour) {
    const glm::vec3 colour(1.0f, 0.25f, 0.5f);
    Scene coloured = floorScene(glm::vec3(0.8f));
    coloured.meshes[0].colors.assign(4, colour);
    const Scene plain = floorScene(glm::vec3(0.8f) * colour);
    const Scene white = floorScene(glm::vec3(0.8f));
    testing::InProcessRenderer a(coloured), b(plain), c(white);
    const Image ia = a.render(4), ib = b.render(4), ic = c.render(4);
    const double same = testing::meanDifference(ia, ib), changed = testing::meanDifference(ia, ic);
    std::printf("vertex colour against base colour %.3g, against white %.3g\n", same, changed);
    EXPECT_LT(same, 1e-3 * changed);
}

TEST(VertexColours, AreInterpolatedAcrossTheTriangles) {
    Scene scene = floorScene(glm::vec3(0.8f));
    // Red on the left (x = -1), blue on the right (x = 1).
    const glm::vec3 red(1, 0, 0), blue(0, 0, 1);
    scene.meshes[0].colors = {red, blue, blue, red};
    testing::InProcessRenderer renderer(scene);
    const Image image = renderer.render(4);
    EXPECT_EQ(renderer.nonFiniteValues(), 0u);
    const int w = image.width, y = image.height / 2;
    const glm::vec3 left = image.pixels[std::size_t(y) * w + 3];
    const glm::vec3 middle = image.pixels[std::size_t(y) * w + w / 2];
    const glm::vec3 right = image.pixels[std::size_t(y) * w + w - 4];
    EXPECT_GT(left.x, 4.0f * left.z);
    EXPECT_GT(right.z, 4.0f * right.x);
    EXPECT_EQ(left.y, 0.0f);  // nothing green anywhere
    EXPECT_GT(middle.x, 0.2f * middle.z);
    EXPECT_GT(middle.z, 0.2f * middle.x);
}

}  // namespace
}  // namespace igi
