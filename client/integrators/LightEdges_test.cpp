#include "integrators/LightEdges.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "testing/TestScenes.h"

namespace igi {
namespace {

const Camera kCamera{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 40.0f};

// Every pixel that a triangle's projected edge crosses is marked, and no pixel farther than
// two pixels from every edge is.
TEST(LightEdges, MarksThePixelsTheOutlineCrossesAndNoOthers) {
    const CameraModel camera(kCamera, 64, 48);
    const glm::vec3 a(-0.9f, -0.7f, 0.0f), b(1.1f, -0.4f, 0.3f), c(0.2f, 0.8f, -0.5f);
    LightEdges edges(camera);
    edges.addTriangle(a, b, c);
    const glm::vec2 p[3] = {camera.pixelOf(a), camera.pixelOf(b), camera.pixelOf(c)};
    auto distanceToOutline = [&](glm::vec2 q) {
        float best = 1e30f;
        for (int i = 0; i < 3; ++i) {
            const glm::vec2 u = p[i], v = p[(i + 1) % 3], d = v - u;
            const float t = std::clamp(glm::dot(q - u, d) / glm::dot(d, d), 0.0f, 1.0f);
            best = std::min(best, glm::length(q - (u + t * d)));
        }
        return best;
    };
    // Crossed: fine steps along each projected edge.
    for (int i = 0; i < 3; ++i)
        for (int s = 0; s <= 1000; ++s) {
            const glm::vec2 q = p[i] + (p[(i + 1) % 3] - p[i]) * (float(s) / 1000.0f);
            EXPECT_TRUE(edges.contains(int(q.x), int(q.y))) << q.x << ", " << q.y;
        }
    std::size_t marked = 0;
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x) {
            marked += edges.contains(x, y);
            // A pixel's centre is within 0.71 of any point of it: farther than 2.2 from the
            // outline, no point of the pixel's 3 x 3 neighbourhood is on it.
            if (distanceToOutline(glm::vec2(x + 0.5f, y + 0.5f)) > 2.2f) {
                EXPECT_FALSE(edges.contains(x, y)) << x << ", " << y;
            }
        }
    EXPECT_EQ(marked, edges.count());
    EXPECT_GT(marked, 0u);
    EXPECT_LT(marked, 64u * 48u / 2u);  // an outline, not the triangle's inside
}

TEST(LightEdges, BehindTheCameraOrAroundTheViewNothingIsMarked) {
    const CameraModel camera(kCamera, 64, 48);
    LightEdges edges(camera);
    edges.addTriangle({-1, -1, 6}, {1, -1, 6}, {0, 1, 7});  // behind the camera
    // Far larger than the view: its edges are all outside the image.
    edges.addTriangle({-100, -100, 0}, {100, -100, 0}, {0, 100, 0});
    EXPECT_EQ(edges.count(), 0u);
}

// A triangle that reaches behind the camera is clipped there: only its part in front of the
// camera is outlined, with finite positions whatever the scene's scale.
TEST(LightEdges, ATriangleThroughTheCameraPlaneIsClipped) {
    for (const float scale : {1e-3f, 1.0f, 1e3f}) {
        Camera c = kCamera;
        c.position *= scale;
        const CameraModel camera(c, 64, 48);
        LightEdges edges(camera);
        // A floor under the camera from behind it to far ahead.
        edges.addTriangle(glm::vec3(-2, -1, 10) * scale, glm::vec3(2, -1, 10) * scale,
                          glm::vec3(0, -1, -20) * scale);
        EXPECT_GT(edges.count(), 0u) << scale;
        EXPECT_LT(edges.count(), 64u * 48u) << scale;
        // The image's top rows look above the floor: no edge of it there.
        for (int x = 0; x < 64; ++x) EXPECT_FALSE(edges.contains(x, 0)) << scale;
    }
}

// A square light facing the camera, on nothing: each pixel's converged value is the light's
// radiance times the share of the pixel it covers. The light's own rays find that share at
// the edge pixels with far less error than one eye ray per frame, and both are unbiased.
Scene squareLight(int edgeRays) {
    Scene scene;
    Material light = testing::diffuse(glm::vec3(0.0f));
    light.emission = glm::vec3(50.0f);
    scene.materials.push_back(light);
    scene.meshes.push_back(
        testing::makeQuad({-0.83f, -0.61f, 0.0f}, {1.71f, 0, 0}, {0, 1.37f, 0}, 0));
    scene.camera = kCamera;
    scene.image = {32, 24, 0};
    scene.render.causticPhotons = 0;
    scene.render.lightEdgeRays = edgeRays;
    return scene;
}

TEST(LightEdges, EdgeRaysFindEachPixelsShareOfTheLight) {
    const CameraModel camera(kCamera, 32, 24);
    const glm::vec2 lo = camera.pixelOf({-0.83f, 0.76f, 0.0f}),
                    hi = camera.pixelOf({0.88f, -0.61f, 0.0f});
    auto expected = [&](int x, int y) {
        const float w = std::max(0.0f, std::min(hi.x, x + 1.0f) - std::max(lo.x, float(x)));
        const float h = std::max(0.0f, std::min(hi.y, y + 1.0f) - std::max(lo.y, float(y)));
        return 50.0 * double(w) * double(h);
    };
    double squared[2] = {0, 0}, total[2] = {0, 0}, truth = 0;
    int edgePixels = 0;
    for (const int rays : {0, 32}) {
        testing::InProcessRenderer renderer(squareLight(rays));
        const Image image = renderer.render(16);
        const int k = rays > 0;
        for (int y = 0; y < 24; ++y)
            for (int x = 0; x < 32; ++x) {
                const double e = expected(x, y), got = image.pixels[std::size_t(y) * 32 + x].x;
                total[k] += got;
                if (k == 0) truth += e;
                if (e > 0.0 && e < 50.0 * 0.999) {  // partly covered
                    squared[k] += (got - e) * (got - e);
                    edgePixels += k == 0;
                }
            }
    }
    ASSERT_GT(edgePixels, 20);
    // Unbiased both ways: the image's light is the square's (its noise over 16 frames is
    // a few tenths of a per cent of it).
    EXPECT_NEAR(total[0] / truth, 1.0, 0.01);
    EXPECT_NEAR(total[1] / truth, 1.0, 0.01);
    // 32 stratified rays per frame against one eye ray: the edge pixels' squared error falls
    // by far more than 10 (about 32^1.5 / 16^0.5 in a model of a straight edge).
    EXPECT_LT(squared[1], squared[0] / 10.0) << squared[1] << " against " << squared[0];
}

}  // namespace
}  // namespace igi
