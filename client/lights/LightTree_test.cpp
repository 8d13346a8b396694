#include "lights/LightTree.h"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "scene/SceneLoader.h"
#include "testing/TestScenes.h"
#include "util/TestPaths.h"

namespace igi {
namespace {

// A grid of small square ceiling lights facing down (y = 3), like the interior scene's, with
// powers that vary by a factor of 4, plus one point light.
std::vector<LightTree::Light> ceilingGrid(int nx, int nz) {
    std::vector<LightTree::Light> lights;
    for (int i = 0; i < nx; ++i)
        for (int k = 0; k < nz; ++k) {
            LightTree::Light l;
            const glm::vec3 c(-4.0f + 8.0f * (float(i) + 0.5f) / float(nx), 3.0f,
                              -3.0f + 6.0f * (float(k) + 0.5f) / float(nz));
            l.lo = c - glm::vec3(0.07f, 0.0f, 0.07f);
            l.hi = c + glm::vec3(0.07f, 0.0f, 0.07f);
            l.normal = {0.0f, -1.0f, 0.0f};
            l.power = 1.0f + float((i + k) % 4);
            lights.push_back(l);
        }
    LightTree::Light point;
    point.lo = point.hi = {1.0f, 1.0f, 1.0f};
    point.omni = true;
    point.power = 3.0f;
    lights.push_back(point);
    return lights;
}

struct Receiver {
    glm::vec3 p, n;
};

std::vector<Receiver> receivers(int count) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> x(-4.0f, 4.0f), y(0.0f, 2.9f), z(-3.0f, 3.0f),
        s(-1.0f, 1.0f);
    std::vector<Receiver> r;
    for (int i = 0; i < count; ++i) {
        glm::vec3 n(s(rng), s(rng), s(rng));
        if (glm::dot(n, n) < 1e-3f) n = {0.0f, 1.0f, 0.0f};
        r.push_back({{x(rng), y(rng), z(rng)}, glm::normalize(n)});
    }
    return r;
}

// The probabilities of all lights sum to one at most (less where the walk meets a node none of
// whose lights can reach the point: sample() fails there, as a sample that brings nothing would
// bring nothing), and the one sample() reports is probability()'s.
TEST(LightTree, ProbabilitiesSumToOneAndAgreeWithSampling) {
    const auto lights = ceilingGrid(12, 8);
    const LightTree tree(lights);
    double sums = 0;
    for (const Receiver& r : receivers(50)) {
        double sum = 0;
        for (std::uint32_t i = 0; i < lights.size(); ++i) sum += tree.probability(r.p, r.n, i);
        ASSERT_LE(sum, 1.0 + 1e-4);
        sums += sum;
        int found = 0;
        LightTree::Memo memo;
        for (int j = 0; j < 4096; ++j) {
            std::uint32_t light = 0;
            float probability = 0;
            if (!tree.sample(r.p, r.n, (float(j) + 0.5f) / 4096.0f, light, probability)) continue;
            ++found;
            EXPECT_FLOAT_EQ(probability, tree.probability(r.p, r.n, light));
            // A memo of earlier walks at the same point changes nothing.
            std::uint32_t again = 0;
            float againProbability = 0;
            ASSERT_TRUE(
                tree.sample(r.p, r.n, (float(j) + 0.5f) / 4096.0f, again, againProbability, &memo));
            EXPECT_EQ(again, light);
            EXPECT_EQ(againProbability, probability);
        }
        // As often as the probabilities say (4096 stratified numbers).
        EXPECT_NEAR(found / 4096.0, sum, 0.005);
    }
    EXPECT_GT(sums / 50, 0.5);  // most receivers face some of the lights
}

// Stratified numbers choose each light as often as its probability says.
TEST(LightTree, ChoicesFollowTheirProbabilities) {
    const auto lights = ceilingGrid(6, 4);
    const LightTree tree(lights);
    const Receiver r{{0.3f, 0.5f, -0.4f}, {0.0f, 1.0f, 0.0f}};
    const int n = 200000;
    std::vector<int> count(lights.size(), 0);
    for (int j = 0; j < n; ++j) {
        std::uint32_t light = 0;
        float probability = 0;
        ASSERT_TRUE(tree.sample(r.p, r.n, (float(j) + 0.5f) / float(n), light, probability));
        ++count[light];
    }
    for (std::uint32_t i = 0; i < lights.size(); ++i)
        EXPECT_NEAR(double(count[i]) / n, tree.probability(r.p, r.n, i), 2.0 / n) << i;
}

// The estimate stays unbiased: every light that can light the point's front side keeps a
// probability above zero, and only lights that cannot get zero.
TEST(LightTree, OnlyLightsThatCannotReachThePointGetZero) {
    const auto lights = ceilingGrid(12, 8);
    const LightTree tree(lights);
    auto reaches = [&](const LightTree::Light& l, const Receiver& r) {
        // Some corner of the light lies in front of the receiver, and the receiver in front of
        // the light.
        for (float a : {0.0f, 1.0f})
            for (float c : {0.0f, 1.0f}) {
                const glm::vec3 q(l.lo.x + a * (l.hi.x - l.lo.x), l.lo.y,
                                  l.lo.z + c * (l.hi.z - l.lo.z));
                const bool front = l.omni || glm::dot(l.normal, r.p - q) > 0;
                if (front && glm::dot(r.n, q - r.p) > 0) return true;
            }
        return false;
    };
    int zeros = 0;
    for (const Receiver& r : receivers(200))
        for (std::uint32_t i = 0; i < lights.size(); ++i) {
            const float p = tree.probability(r.p, r.n, i);
            if (reaches(lights[i], r)) {
                EXPECT_GT(p, 0.0f) << i;
            }
            zeros += p == 0;
        }
    EXPECT_GT(zeros, 0);  // receivers facing down see none of the ceiling
    // Above the lights, facing up, nothing reaches.
    std::uint32_t light = 0;
    float probability = 0;
    LightTree::Light only = lights[0];
    const LightTree one(std::vector<LightTree::Light>{only});
    EXPECT_FALSE(one.sample({0.0f, 3.5f, 0.0f}, {0.0f, 1.0f, 0.0f}, 0.5f, light, probability));
    EXPECT_EQ(one.probability({0.0f, 3.5f, 0.0f}, {0.0f, 1.0f, 0.0f}, 0), 0.0f);
}

// The point of the tree: a point right under a light, facing it, chooses that light far more
// often than its share of the power (1 / 97 of the lights, 0.4 % of the power; measured 0.16).
TEST(LightTree, ANearbyLightIsChosenFarMoreOftenThanByPower) {
    const auto lights = ceilingGrid(12, 8);
    const LightTree tree(lights);
    const std::uint32_t i = 5 * 8 + 3;
    const glm::vec3 under = 0.5f * (lights[i].lo + lights[i].hi) - glm::vec3(0.0f, 0.4f, 0.0f);
    double total = 0;
    for (const auto& l : lights) total += l.power;
    const float p = tree.probability(under, {0.0f, 1.0f, 0.0f}, i);
    EXPECT_GT(p, 0.1f);
    EXPECT_GT(p, 15.0 * lights[i].power / total);
}

TEST(LightTree, DegenerateInputs) {
    const LightTree none{std::vector<LightTree::Light>{}};
    std::uint32_t light = 0;
    float probability = 0;
    EXPECT_FALSE(none.sample({0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 0.5f, light, probability));
    // A receiver on a point light, and lights of no power beside one that has some.
    std::vector<LightTree::Light> lights(3);
    for (auto& l : lights) l.omni = true;
    lights[1].power = 2.0f;
    const LightTree tree(lights);
    ASSERT_TRUE(tree.sample({0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, 0.9f, light, probability));
    EXPECT_EQ(light, 1u);
    EXPECT_FLOAT_EQ(probability, 1.0f);
    EXPECT_TRUE(std::isfinite(tree.probability({0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 1)));
}

// Rendered: the interior (96 small lights) with the tree and with power sampling converges to
// the same image, for IGI and for the path tracer, and the tree's one frame is less noisy.
Scene interior(LightSampling sampling) {
    Scene scene = loadSceneFile(testing::sourceDir() / "scenes/interior/diffuse.json");
    scene.image.width = 64;
    scene.image.height = 48;
    scene.render.lightSampling = sampling;
    return scene;
}

TEST(LightTree, InteriorConvergesToTheSameImageWithTreeAndPowerSampling) {
    for (IntegratorKind kind : {IntegratorKind::Igi, IntegratorKind::Path}) {
        Scene tree = interior(LightSampling::Tree), power = interior(LightSampling::Power);
        tree.render.integrator = power.render.integrator = kind;
        const int frames = kind == IntegratorKind::Igi ? 64 : 8;
        testing::InProcessRenderer a(tree), b(power);
        const glm::dvec3 ma = testing::meanOf(a.render(frames));
        const glm::dvec3 mb = testing::meanOf(b.render(frames));
        EXPECT_EQ(a.nonFiniteValues(), 0u);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(ma[c] / mb[c], 1.0, 0.01) << int(kind) << c;
    }
}

}  // namespace
}  // namespace igi
