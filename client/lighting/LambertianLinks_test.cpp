#include "lighting/LambertianLinks.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

namespace igi {
namespace {

bool sameBits(float a, float b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

// The scalar connection of EndPointShader (linkTo, then the clamped Lambertian term), the
// reference every lane must equal bit for bit.
bool scalarLink(const Vpl& v, glm::vec3 origin, glm::vec3 n, glm::vec3 f, float dmin2,
                LambertianLink& out) {
    const glm::vec3 toLight = v.position - origin;
    const float d2 = glm::dot(toLight, toLight);
    if (!(d2 > 0)) return false;
    const float d = std::sqrt(d2);
    const glm::vec3 w = toLight / d;
    const float cosX = glm::dot(n, w);
    if (cosX <= 0 || glm::dot(f, w) <= 0) return false;
    const float cosY = -glm::dot(v.normal, w);
    if (cosY <= 0) return false;
    out = {0, d, w, cosX * cosY / std::max(d2, dmin2)};
    return true;
}

// The VPLs the caller connects itself: glossy ones, and light samples of point lights (whose
// cosine is 1, which the lanes do not compute).
bool general(const Vpl& v) {
    return v.glossy() || v.omni;
}

glm::vec3 randomUnit(std::mt19937& random) {
    std::normal_distribution<float> g;
    return glm::normalize(glm::vec3(g(random), g(random), g(random)));
}

// Every count of VPLs (the lanes' remainders), glossy VPLs and omni light samples among them,
// points at a VPL's own position (d = 0) and far from all: both instruction sets keep the scalar
// tests' VPLs and give their values with the same bits.
TEST(LambertianLinks, EveryInstructionSetGivesTheScalarConnectionsBitForBit) {
    std::mt19937 random(17);
    std::uniform_real_distribution<float> u(-3.0f, 3.0f);
    std::vector<lanes::Isa> isas = {lanes::Isa::kBaseline};
    if (lanes::hasAvx2()) isas.push_back(lanes::Isa::kAvx2);
    int kept = 0, generalListed = 0, checked = 0;
    LinkBuffer got;  // one for every call, as a thread's: what a call left must not show
    for (int count = 1; count <= 37; ++count) {
        std::vector<Vpl> vpls(static_cast<std::size_t>(count));
        for (std::size_t i = 0; i < vpls.size(); ++i) {
            vpls[i].position = {u(random), u(random), u(random)};
            vpls[i].normal = randomUnit(random);
            vpls[i].power = glm::vec3(1.0f);
            if (i % 5 == 3) vpls[i].glossyShare = 0.5f;
            if (i % 7 == 5) vpls[i].omni = true;
        }
        VplChoice choice;
        choice.prepare(vpls, 0, 0.5f);
        for (int p = 0; p < 40; ++p) {
            const glm::vec3 origin =
                p == 0 ? vpls[0].position : glm::vec3(u(random), u(random), u(random));
            const glm::vec3 n = randomUnit(random);
            const glm::vec3 f = glm::normalize(n + 0.3f * randomUnit(random));
            const float dmin2 = p % 2 ? 0.25f : 0.0f;
            std::vector<LambertianLink> expected;
            for (std::size_t i = 0; i < vpls.size(); ++i) {
                LambertianLink l{};
                const bool linked = scalarLink(vpls[i], origin, n, f, dmin2, l);
                if (!linked && !general(vpls[i])) continue;
                l.vpl = std::uint32_t(i);
                expected.push_back(l);
                kept += linked;
                generalListed += !linked;
            }
            for (const lanes::Isa isa : isas) {
                const std::size_t links =
                    lambertianLinks(choice, vpls.size(), origin, n, f, dmin2, got, isa);
                ASSERT_EQ(links, got.size());
                ASSERT_EQ(got.size(), expected.size()) << "count " << count << ", point " << p;
                for (std::size_t k = 0; k < got.size(); ++k) {
                    const LambertianLink a = got[k], &e = expected[k];
                    ASSERT_EQ(a.vpl, e.vpl);
                    if (general(vpls[a.vpl])) continue;  // the caller recomputes those
                    ASSERT_TRUE(sameBits(a.d, e.d) && sameBits(a.w.x, e.w.x) &&
                                sameBits(a.w.y, e.w.y) && sameBits(a.w.z, e.w.z) &&
                                sameBits(a.g, e.g))
                        << "VPL " << a.vpl << " of " << count << ", isa " << int(isa);
                    ++checked;
                }
            }
        }
    }
    EXPECT_GT(kept, 1000) << "the tests keep a fair share of the VPLs";
    EXPECT_GT(generalListed, 100)
        << "glossy VPLs and omni light samples are listed even where the tests reject them";
    EXPECT_GT(checked, 1000);
}

}  // namespace
}  // namespace igi
