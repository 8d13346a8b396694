#include "lights/VplWeights.h"

#include <algorithm>
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "math/Color.h"
#include "testing/TestVpls.h"

namespace igi {
namespace {

// `count` VPLs over a room, every third (from the second) a GGX metal lobe: both the plain
// lanes and the ranked ones.
std::vector<Vpl> roomVpls(int count, std::mt19937& random) {
    return testing::roomVpls(count, random, {.ggxEveryThird = true});
}

struct Weights {
    std::vector<float> weight, sumW, sumR;
    explicit Weights(std::size_t n) : weight(n), sumW(n), sumR(n) {}
    bool operator==(const Weights& o) const {  // bit for bit (memcmp: -0 and NaN included)
        auto same = [](const std::vector<float>& a, const std::vector<float>& b) {
            return a.size() == b.size() &&
                   std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
        };
        return same(weight, o.weight) && same(sumW, o.sumW) && same(sumR, o.sumR);
    }
};

Weights weighed(const VplChoice& c, glm::vec3 x, glm::vec3 n, const SurfaceBrdf* receiver,
                lanes::Isa isa) {
    Weights w(c.lum.size());
    vplWeights(c, x, n, n, 0.04f, receiver != nullptr, receiver, w.weight.data(), w.sumW.data(),
               w.sumR.data(), isa);
    return w;
}

// The eight-lane kernel gives the four-lane one's bits, for pools that end on a group of eight
// or of four, with and without a GGX receiver: a pixel's choice must not depend on whether
// its client's processor has AVX2.
TEST(VplWeights, EightLanesGiveTheBitsOfFour) {
    if (!lanes::hasAvx2()) GTEST_SKIP() << "no AVX2 here";
    std::mt19937 random(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const glm::vec3 view = glm::normalize(glm::vec3(0.3f, 1.0f, 0.5f));
    for (int count : {1, 3, 4, 5, 8, 12, 16, 61, 144, 170}) {
        VplChoice c;
        c.prepare(roomVpls(count, random), 18, 0.5f);
        for (int p = 0; p < 20; ++p) {
            const glm::vec3 x(4 * u(random) - 2, 1.5f * u(random), 3 * u(random) - 1.5f);
            const glm::vec3 n = glm::normalize(glm::vec3(u(random) - 0.5f, 1.0f, u(random) - 0.5f));
            const SurfaceBrdf ggx = SurfaceBrdf::makeGgx(glm::vec3(0.05f), glm::vec3(0.8f), 0.15f,
                                                         n, 2.0f * glm::dot(n, view) * n - view);
            for (const SurfaceBrdf* receiver : {static_cast<const SurfaceBrdf*>(nullptr), &ggx})
                EXPECT_TRUE(weighed(c, x, n, receiver, lanes::Isa::kBaseline) ==
                            weighed(c, x, n, receiver, lanes::Isa::kAvx2))
                    << count << " VPLs, point " << p;
        }
    }
}

// Without GGX lobes a weight is the clamped Lambertian importance in the scalar order,
// lum cx cy / (d^2 max(d^2, dmin^2)), zero where the VPL cannot light the point; the sums run
// over the weights and over the reachable VPLs.
TEST(VplWeights, LambertianWeightsAreTheScalarImportance) {
    std::mt19937 random(7);
    std::vector<Vpl> vpls = roomVpls(37, random);
    for (Vpl& v : vpls) v = Vpl{v.position, v.normal, v.power};
    VplChoice c;
    c.prepare(vpls, 18, 0.5f);
    const glm::vec3 x(0.5f, 0.0f, 0.2f), n(0, 1, 0);
    for (lanes::Isa isa : {lanes::Isa::kBaseline, lanes::bestIsa()}) {
        const Weights w = weighed(c, x, n, nullptr, isa);
        float reachable = 0;
        for (std::size_t i = 0; i < vpls.size(); ++i) {
            const glm::vec3 t = vpls[i].position - x;
            const float d2 = glm::dot(t, t), cx = glm::dot(n, t), cy = -glm::dot(vpls[i].normal, t);
            const float lum = luminance(vpls[i].power);
            const float expected = lum * cx * cy / (d2 * std::max(d2, 0.04f));
            const bool can = cx > 0 && cy > 0 && expected > 0;
            EXPECT_EQ(w.weight[i], can ? expected : 0.0f) << i;
            reachable += can ? 1.0f : 0.0f;
        }
        EXPECT_EQ(w.sumR[vpls.size() - 1], reachable);
        EXPECT_EQ(w.sumR.back(), reachable);  // the padding reaches nothing
        EXPECT_NEAR(
            w.sumW.back(),
            [&] {
                float s = 0;
                for (float v : w.weight) s += v;
                return s;
            }(),
            1e-5f * w.sumW.back());
    }
}

}  // namespace
}  // namespace igi
