#include "modes/spt/SelectiveLighting.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <gtest/gtest.h>

#include "SceneVersion.h"
#include "sampling/HaltonPaths.h"
#include "testing/TestEpochs.h"
#include "testing/TestScenes.h"
#include "tracing/EmbreeDevice.h"
#include "tracing/SceneGeometry.h"

namespace igi {
namespace {

constexpr std::uint32_t kBox = 5;     // cornellBox's turned box
constexpr std::uint32_t kHidden = 6;  // a box behind the back wall, where no light goes

Scene sptBox() {
    Scene s = testing::cornellBox(1.0f);
    s.meshes.push_back(testing::makeBox({0.5f, 0.5f, -0.6f}, glm::vec3(0.2f), 0.0f, 0));
    s.render.gi = GiMode::Spt;
    s.render.sptGroups = 36;
    s.render.sptPaths = 4;
    s.render.sptPilots = 1;
    s.render.sptBudget = 5;
    return s;
}

using Epochs = testing::Epochs<SelectiveLighting>;

double torusDistance(float a, float b) {
    const double d = std::abs(double(a) - double(b));
    return std::min(d, 1.0 - d);
}

// The paper's equation 3: with G = 2^2 3^2, paths g and g + m G agree in the base-2 dimension
// to 1/4 and in the base-3 one to 1/9 (modulo 1: the random shift wraps).
TEST(HaltonPaths, PathsOfAGroupStartAlike) {
    const std::uint32_t groups = 36;
    for (std::uint32_t g = 0; g < groups; g += 5) {
        const HaltonPaths paths(7, groups, g, 0, 20);
        for (std::uint32_t j = 1; j < 20; ++j) {
            EXPECT_LT(torusDistance(paths.emission(j, 3), paths.emission(0, 3)), 0.25);
            EXPECT_LT(torusDistance(paths.emission(j, 4), paths.emission(0, 4)), 1.0 / 9.0);
        }
    }
    EXPECT_EQ(HaltonPaths::base(3), 2u);
    EXPECT_EQ(HaltonPaths::base(4), 3u);
    EXPECT_EQ(HaltonPaths::base(0), 5u);
    // Different groups do not: over all groups, the base-2 dimension spreads over [0, 1).
    float lo = 1, hi = 0;
    for (std::uint32_t g = 0; g < groups; ++g) {
        const float u = HaltonPaths(7, groups, g, 0, 1).emission(0, 3);
        lo = std::min(lo, u);
        hi = std::max(hi, u);
    }
    EXPECT_GT(hi - lo, 0.7f);
}

TEST(HaltonPaths, RadicalInverseMirrorsTheDigits) {
    EXPECT_DOUBLE_EQ(radicalInverse(1, 2), 0.5);
    EXPECT_DOUBLE_EQ(radicalInverse(6, 2), 0.375);        // 110 -> 0.011
    EXPECT_NEAR(radicalInverse(5, 3), 7.0 / 9.0, 1e-15);  // 12 -> 0.21
}

TEST(SelectiveLighting, AChangeThatTouchesNoPathTracesNothing) {
    Epochs client(sptBox());
    const SceneState still = SceneState::of(client.scene());
    const auto before = client.begin(still, 0).poolAt(0);
    EXPECT_EQ(before->update().traced, 36u);
    SceneState moved = still;
    moved.transforms[kHidden].translate += glm::vec3(0.1f, 0.05f, -0.1f);
    const auto after = client.begin(moved, 1).poolAt(1);
    EXPECT_EQ(after->update().touched, 0u);
    EXPECT_EQ(after->update().traced, 0u);
    EXPECT_EQ(after->invalidCount(), 0u);
    EXPECT_EQ(after->groups(), before->groups()) << "every group kept, not a copy traced again";
    // The camera alone: nothing to check, not even pilots.
    SceneState turned = moved;
    turned.camera.position.x += 0.1f;
    const auto camera = client.begin(turned, 2).poolAt(2);
    EXPECT_EQ(camera->update().pilotGroups, 0u);
    EXPECT_EQ(camera->update().traced, 0u);
}

TEST(SelectiveLighting, TouchedGroupsAreTracedAgainWithinTheBudgetOldestFirst) {
    Epochs client(sptBox());
    const SceneState still = SceneState::of(client.scene());
    const auto before = client.begin(still, 0).poolAt(0);
    SceneState moved = still;
    moved.transforms[kBox].translate += glm::vec3(-0.15f, 0.0f, 0.1f);
    const SelectiveLighting& epoch = client.begin(moved, 1);
    const auto first = epoch.poolAt(1);
    const std::uint32_t touched = first->update().touched;
    EXPECT_GT(touched, 5u) << "the box is in the way of many paths";
    EXPECT_LT(touched, 36u) << "but not of all: the pilots and the paths' own hits decide";
    EXPECT_EQ(first->update().traced, 5u);
    EXPECT_EQ(first->invalidCount(), touched - 5);
    // The scene then holds still: each frame traces the budget again until none waits.
    const std::uint32_t frames = (touched + 4) / 5;
    for (std::uint32_t f = 2; f <= frames; ++f)
        EXPECT_EQ(epoch.poolAt(f)->invalidCount(), touched > 5 * f ? touched - 5 * f : 0u);
    const auto settled = epoch.poolAt(frames + 10);
    EXPECT_EQ(settled->invalidCount(), 0u);
    // Every group touched is now what tracing it on the new scene gives; the others are the
    // same objects as before the change.
    std::uint32_t retraced = 0;
    for (std::uint32_t g = 0; g < 36; ++g) {
        const PhotonGroup& group = *settled->groups()[g];
        if (settled->groups()[g] == before->groups()[g]) continue;
        ++retraced;
        EXPECT_EQ(group.scene->transforms[kBox], moved.transforms[kBox]);
        EXPECT_GE(group.tracedFrame, 1u);
        EXPECT_LE(group.tracedFrame, frames);
    }
    EXPECT_EQ(retraced, touched);
    // Oldest first: the frame-1 batch are the lowest indices among the touched (all equally
    // old), so the tracing frames do not decrease with the index.
    std::uint32_t last = 0;
    for (std::uint32_t g = 0; g < 36; ++g) {
        if (settled->groups()[g] == before->groups()[g]) continue;
        EXPECT_GE(settled->groups()[g]->tracedFrame, last);
        last = settled->groups()[g]->tracedFrame;
    }
}

TEST(SelectiveLighting, ALightChangeTouchesEveryGroup) {
    Epochs client(sptBox());
    const SceneState still = SceneState::of(client.scene());
    client.begin(still, 0);
    SceneState dimmed = still;
    dimmed.quadLights[0].radiance *= 0.5f;
    const auto pool = client.begin(dimmed, 4).poolAt(4);
    EXPECT_EQ(pool->update().touched, 36u);
    EXPECT_EQ(pool->update().pilotGroups, 0u) << "no pilot needed to know";
}

// The pool of a frame depends on the scene of every frame, not on which frames a client
// rendered: asking for frame 6 first gives what asking frame by frame gives.
TEST(SelectiveLighting, APoolIsTheSameWhicheverFramesWereAskedFor) {
    Epochs a(sptBox()), b(sptBox());
    const SceneState still = SceneState::of(a.scene());
    SceneState moved = still;
    moved.transforms[kBox].translate.x -= 0.2f;
    a.begin(still, 0);
    b.begin(still, 0);
    const SelectiveLighting& ea = a.begin(moved, 3);
    const SelectiveLighting& eb = b.begin(moved, 3);
    for (std::uint32_t f = 3; f <= 6; ++f) ea.poolAt(f);
    const auto pa = ea.poolAt(6), pb = eb.poolAt(6);
    for (std::uint32_t g = 0; g < 36; ++g) {
        EXPECT_EQ(pa->groups()[g]->tracedFrame, pb->groups()[g]->tracedFrame);
        ASSERT_EQ(pa->groups()[g]->vpls.size(), pb->groups()[g]->vpls.size());
        for (std::size_t i = 0; i < pa->groups()[g]->vpls.size(); ++i)
            EXPECT_EQ(pa->groups()[g]->vpls[i].position, pb->groups()[g]->vpls[i].position);
    }
}

// The pool carries the lights' power: as much as IGI's light paths deliver to the first
// bounce and beyond, within the noise of 144 paths.
TEST(SelectiveLighting, ThePoolsVplsCarryTheLightOfIgis) {
    Epochs client(sptBox());
    const SelectiveLighting& m = client.begin(SceneState::of(client.scene()), 0);
    const int sets = client.scene().render.setCount();
    double pool = 0;
    for (std::uint32_t k = 0; k < std::uint32_t(sets); ++k)
        for (const Vpl& v : m.build(0, 0, k).indirect) pool += double(luminance(v.power));
    EXPECT_GT(pool, 0.0);
    // Every set's VPLs are K times their share: the sets' mean is the pool's total.
    testing::InProcessRenderer igi([] {
        Scene s = sptBox();
        s.render.gi = GiMode::Igi;
        s.render.roulette = true;
        return s;
    }());
    double reference = 0;
    const int frames = 16;
    for (int f = 0; f < frames; ++f)
        for (std::uint32_t k = 0; k < std::uint32_t(sets); ++k)
            for (const Vpl& v : igi.renderer().builder().build(std::uint32_t(f), 1, k).indirect)
                reference += double(luminance(v.power));
    reference /= double(frames);
    EXPECT_NEAR(pool / double(sets) / (reference / double(sets)), 1.0, 0.25);
}

}  // namespace
}  // namespace igi
