#include "modes/photonmap/PhotonEmission.h"

#include <memory>

#include <gtest/gtest.h>

#include "SceneVersion.h"
#include "modes/photonmap/PhotonMap.h"
#include "modes/photonmap/PhotonMapLighting.h"
#include "testing/TestEpochs.h"
#include "testing/TestScenes.h"

namespace igi {
namespace {

constexpr std::uint32_t kBox = 5;  // cornellBox's turned box

Scene photonBox() {
    Scene s = testing::cornellBox(1.0f);
    s.render.gi = GiMode::PhotonMap;
    s.render.photonmapGroups = 64;
    s.render.photonmapPhotons = 8;
    s.render.cacheSpacing = 0.05f;
    s.render.photonmapGather = 16;
    return s;
}

using Epochs = testing::Epochs<PhotonMapLighting>;

bool sameHits(const PhotonEmission& a, const PhotonEmission& b) {
    const auto ha = a.hits(), hb = b.hits();
    if (ha.size() != hb.size()) return false;
    for (std::size_t i = 0; i < ha.size(); ++i)
        if (!(ha[i] == hb[i])) return false;
    return true;
}

// A still scene checks one photon of each group per frame and retraces nothing; after every
// photon has been checked once the state is settled and every later frame holds it unchanged.
TEST(PhotonEmission, AStillSceneRetracesNothingAndSettles) {
    Epochs client(photonBox());
    const auto& m = client.begin(SceneState::of(client.scene()), 0);
    const auto first = m.emissionAt(0);
    EXPECT_EQ(first->update().traced, 64u);
    for (std::uint32_t f = 1; f < 8; ++f) {
        const auto e = m.emissionAt(f);
        EXPECT_EQ(e->update().traced, 0u) << f;
        EXPECT_EQ(e->version(), first->version());
    }
    EXPECT_TRUE(m.emissionAt(8)->settled(SceneState::of(client.scene()), 8, 8));
    EXPECT_EQ(m.emissionAt(100), m.emissionAt(8));
}

// A moved object diverts some photons: within P frames every group whose photons meet it is
// found by its round-robin photon and traced again whole, the others kept; the emission then
// equals what every client holds, whichever frames it rendered.
TEST(PhotonEmission, AMoveRetracesTheGroupsItDivertsWithinAGroupsPhotons) {
    Epochs a(photonBox()), b(photonBox());
    SceneState still = SceneState::of(a.scene());
    a.begin(still, 0);
    b.begin(still, 0);
    SceneState moved = still;
    moved.transforms[kBox].translate = {-0.3f, 0.0f, 0.15f};
    const auto& ma = a.begin(moved, 10);
    const auto& mb = b.begin(moved, 10);
    std::uint32_t traced = 0;
    for (std::uint32_t f = 10; f < 18; ++f) traced += ma.emissionAt(f)->update().traced;
    EXPECT_GT(traced, 4u);
    EXPECT_LT(traced, 64u);
    // Client b asks for frame 17 only: the same photons.
    EXPECT_TRUE(sameHits(*ma.emissionAt(17), *mb.emissionAt(17)));
    // Settled: every group's photons now take their paths in the moved scene.
    const auto settled = ma.emissionAt(18);
    EXPECT_TRUE(settled->settled(moved, 18, 8));
    EXPECT_EQ(ma.emissionAt(40), settled);
}

// A light that is dimmed leaves every photon's path as it was, but not its power: every group
// is traced again at once, and the photons carry the new power.
TEST(PhotonEmission, ADimmedLightRetracesEveryGroup) {
    Epochs client(photonBox());
    SceneState still = SceneState::of(client.scene());
    const auto before = client.begin(still, 0).emissionAt(0);
    SceneState dimmed = still;
    // Every light at half: each photon leaves from where it did, with half the power.
    for (auto& l : dimmed.quadLights) l.radiance *= 0.5f;
    for (auto& l : dimmed.punctualLights) l.intensity *= 0.5f;
    const auto after = client.begin(dimmed, 10).emissionAt(10);
    EXPECT_EQ(after->update().traced, 64u);
    const auto a = before->hits(), b = after->hits();
    ASSERT_EQ(a.size(), b.size());
    ASSERT_FALSE(a.empty());
    EXPECT_NEAR(b[0].power.x / a[0].power.x, 0.5f, 1e-4f);
}

// The photon map's estimate of a uniformly lit plane is the density of its hits' power (each
// hit's power being its photon's flux times kd / pi, that density is the radiance).
TEST(PhotonMap, RadianceOfAnEvenlyLitPlane) {
    std::vector<Vpl> hits;
    SplitMix64 random(9);
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        Vpl v;
        v.position = {random.uniform() * 2.0f, 0.0f, random.uniform() * 2.0f};
        v.normal = {0, 1, 0};
        v.power = glm::vec3(1e-3f);
        hits.push_back(v);
    }
    const PhotonMap map(hits, 4.0, 64);
    // n p / area.
    const float expected = float(n) * 1e-3f / 4.0f;
    double sum = 0;
    for (int i = 0; i < 50; ++i) {
        const glm::vec3 p(0.4f + 1.2f * random.uniform(), 0.0f, 0.4f + 1.2f * random.uniform());
        sum += map.radiance(p, {0, 1, 0}).x;
    }
    EXPECT_NEAR(sum / 50 / expected, 1.0, 0.05);
    // The other side of the plane sees none of them.
    EXPECT_EQ(map.radiance({1, 0, 1}, {0, -1, 0}).x, 0.0f);
}

}  // namespace
}  // namespace igi
