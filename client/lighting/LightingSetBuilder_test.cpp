#include "lighting/LightingSetBuilder.h"

#include <cmath>

#include <gtest/gtest.h>

#include "math/Color.h"
#include "math/Warp.h"
#include "render/ProgressiveSchedule.h"
#include "testing/TestScenes.h"

namespace igi {
namespace {

using testing::InProcessRenderer;

Scene diffuseRoomWithPointLight() {
    Scene scene;
    scene.materials.push_back(testing::diffuse(glm::vec3(0.6f)));
    scene.meshes.push_back(testing::makeIcosphere(2, 3.0f, glm::vec3(0), 0));
    scene.punctualLights.push_back(pointLight("lamp", glm::vec3(0, 1, 0), glm::vec3(5)));
    scene.camera = {glm::vec3(0, 0, 2), glm::vec3(0), glm::vec3(0, 1, 0), 60};
    scene.image = {16, 16, 0};
    return scene;
}

TEST(LightingSetBuilder, ASceneWithoutMirrorsOrGlassShootsNoCausticPhotons) {
    InProcessRenderer r(diffuseRoomWithPointLight());
    EXPECT_FALSE(r.renderer().builder().causticsActive());
    for (std::uint32_t k = 0; k < 9; ++k) {
        const LightingSet set = r.renderer().builder().build(0, k);
        EXPECT_EQ(set.photonsShot, 0u);
        EXPECT_TRUE(set.caustics.photons().empty());
        EXPECT_FALSE(set.indirect.empty());
    }
}

TEST(LightingSetBuilder, SameFrameAndSetGiveTheSameVplsOnEveryBuild) {
    InProcessRenderer a(diffuseRoomWithPointLight()), b(diffuseRoomWithPointLight());
    const LightingSet s1 = a.renderer().builder().build(7, 4),
                      s2 = b.renderer().builder().build(7, 4);
    ASSERT_EQ(s1.indirect.size(), s2.indirect.size());
    for (std::size_t i = 0; i < s1.indirect.size(); ++i) {
        EXPECT_EQ(s1.indirect[i].position, s2.indirect[i].position);
        EXPECT_EQ(s1.indirect[i].power, s2.indirect[i].power);
    }
    const LightingSet other = a.renderer().builder().build(8, 4);
    EXPECT_NE(other.indirect.front().position,
              s1.indirect.front().position);  // new frame, new bit vectors
}

TEST(LightingSetBuilder, IndirectVplCountFollowsTheWantedNumber) {
    // A closed room: every light path hits something, so the count is what Keller's walk plans.
    Scene scene = diffuseRoomWithPointLight();
    scene.render.indirectVpls = 18;
    scene.render.roulette = false;  // the paper's walk, whose count is fixed
    InProcessRenderer r(scene);
    const auto& builder = r.renderer().builder();
    std::uint32_t planned = 0;
    for (std::uint32_t d = 0; d + 1 < std::uint32_t(scene.render.maxLightPathLength); ++d)
        planned += builder.survivors(d);
    EXPECT_GE(planned, 18u);
    EXPECT_EQ(builder.build(0, 0).indirect.size(), planned);
    // The lamp is the scene's one light and an exact one: one sample, none chosen.
    EXPECT_EQ(builder.build(0, 0).exact.size(), 1u);
    EXPECT_EQ(builder.build(0, 0).direct.size(), 0u);
}

// With roulette the paper's walk is unchanged up to its length (the same VPLs, in the same
// order), and the paths alive at its end go on by Russian roulette: on a grey surface a path
// survives with probability equal to the albedo and keeps its flux, so the VPLs past the walk
// all carry the power of the walk's last ones.
TEST(LightingSetBuilder, RouletteContinuesThePapersWalk) {
    Scene scene = diffuseRoomWithPointLight();
    scene.render.indirectVpls = 18;
    scene.render.roulette = false;
    InProcessRenderer paper(scene);
    scene.render.roulette = true;
    InProcessRenderer roulette(scene);
    std::size_t extra = 0, firstFrames = 0, longest = 0;
    for (std::uint32_t f = 0; f < 100; ++f) {
        // The walk goes on in the first frame after a change as in the accumulated ones.
        const LightingSet a = paper.renderer().builder().build(f, f % 2, f % 9),
                          b = roulette.renderer().builder().build(f, f % 2, f % 9);
        // The walk's VPLs come path by path: those of b that a also has are a's, in order.
        std::size_t matched = 0;
        for (const Vpl& v : b.indirect)
            if (matched < a.indirect.size() && v.position == a.indirect[matched].position) {
                ASSERT_EQ(v.power, a.indirect[matched].power);
                ++matched;
            }
        ASSERT_EQ(matched, a.indirect.size()) << "frame " << f;
        extra += b.indirect.size() - a.indirect.size();
        if (f % 2 == 0) firstFrames += b.indirect.size() - a.indirect.size();
        longest = std::max(longest, b.indirect.size());
    }
    std::printf("roulette: %.2f VPLs per set past the paper's walk\n", double(extra) / 100);
    EXPECT_GT(extra, 100u) << "paths go on past the walk";
    EXPECT_GT(firstFrames, 50u) << "in the first frames after a change too";
}

// The caustic gather radius shrinks with the frame's place in the accumulation, as progressive
// photon mapping says, and the bound's distance shrinks only when asked to (and is wider with
// Kollig-Keller compensation, from the first frame on).
TEST(LightingSetBuilder, ProgressiveRadiusAndShrinkingClamp) {
    Scene scene = testing::cornellBox(1.0f, /*glassBall=*/true);
    InProcessRenderer r(scene);
    const auto& builder = r.renderer().builder();
    const LightingSet first = builder.build(5, 0, 2), later = builder.build(5, 40, 2);
    const double scale = progressiveScale(scene.render.progressiveAlpha, 40);
    EXPECT_LT(scale, 0.5);
    EXPECT_NEAR(later.caustics.radius() / first.caustics.radius(), std::sqrt(scale), 1e-5);
    // Kollig-Keller: the bound is wider than the paper's by a constant factor, what it removes
    // being restored, in every frame alike (the first frame's cut by the frames after it).
    const float wider = LightingSetBuilder::kCompensatedClampScale;
    Scene without = scene;
    without.render.clampCompensation = ClampCompensation::Off;
    InProcessRenderer papers(without);
    const float paper2 = papers.renderer().builder().build(5, 0, 2).minDistance2;
    EXPECT_GT(paper2, 0.0f);
    EXPECT_FLOAT_EQ(first.minDistance2, paper2 * wider * wider);
    // The other modes' first frames (their VPLs given) keep the paper's bound.
    EXPECT_FLOAT_EQ(builder.buildDirect(5, 2).minDistance2, paper2);
    EXPECT_EQ(later.minDistance2, first.minDistance2);
    EXPECT_EQ(builder.build(5, 1, 2).minDistance2, later.minDistance2);
    EXPECT_EQ(first.compensationShare, 0.0f);  // the cut is restored from the second frame on
    EXPECT_GT(later.compensationShare, 0.0f);
    scene.render.clampCompensation = ClampCompensation::Shrink;
    scene.render.progressiveRadius = false;
    InProcessRenderer shrinking(scene);
    const LightingSet a = shrinking.renderer().builder().build(5, 0, 2),
                      b = shrinking.renderer().builder().build(5, 40, 2);
    EXPECT_NEAR(b.minDistance2 / a.minDistance2, scale, 1e-5);
    EXPECT_EQ(a.caustics.radius(), b.caustics.radius());
}

// IGI's first frame after a change restores nothing of the bound's cut: its glossy points'
// compensation rays do not shade where they land. The frames after it, and the other modes'
// first frames (their VPLs given), restore the cut.
TEST(LightingSetBuilder, TheFirstFrameShadesNoSecondPoint) {
    Scene scene = testing::cornellBox(1.0f, /*glassBall=*/true);
    InProcessRenderer r(scene);
    const auto& builder = r.renderer().builder();
    const LightingSet first = builder.build(5, 0, 2), later = builder.build(5, 1, 2),
                      direct = builder.buildDirect(5, 2);
    EXPECT_FALSE(first.compensationRays);
    EXPECT_EQ(first.sharpnessBudget, LightingSetBuilder::kFirstFrameSharpnessBudget);
    EXPECT_TRUE(later.compensationRays);
    EXPECT_EQ(later.sharpnessBudget, scene.render.glossyBound);
    EXPECT_TRUE(direct.compensationRays);
    EXPECT_EQ(direct.sharpnessBudget, LightingSetBuilder::kFirstFrameSharpnessBudget);
}

// The schedule itself: r_1^2 / r_0^2 = (1 + alpha) / 2, and it falls like i^(alpha - 1).
TEST(ProgressiveSchedule, FollowsKnausAndZwicker) {
    EXPECT_EQ(progressiveScale(0.7, 0), 1.0);
    EXPECT_NEAR(progressiveScale(0.7, 1), 0.85, 1e-12);
    EXPECT_NEAR(progressiveScale(0.7, 2), 0.85 * 2.7 / 3.0, 1e-12);
    const double a = progressiveScale(2.0 / 3.0, 1000), b = progressiveScale(2.0 / 3.0, 8000);
    EXPECT_NEAR(std::log(b / a) / std::log(8.0), -1.0 / 3.0, 0.01);
    EXPECT_EQ(progressiveScale(0.0, 100), 1.0);  // no alpha: no shrinking
}

// A point light below a square mirror facing down, above a large diffuse floor: every photon
// aimed at the mirror reflects onto the floor, so the photons' total power is the mirror's
// reflectance times the intensity times the solid angle the mirror subtends.
TEST(LightingSetBuilder, CausticPowerMatchesTheAnalyticFluxThroughAMirror) {
    Scene scene;
    scene.materials.push_back(testing::diffuse(glm::vec3(0.5f)));
    Material mirror;
    mirror.name = "mirror";
    mirror.diffuse = glm::vec3(0.0f);
    mirror.specular = glm::vec3(0.8f);
    mirror.reflection = Reflection::Mirror;
    scene.materials.push_back(mirror);
    const float half = 0.5f, height = 1.0f;  // the mirror is 1 x 1, one unit above the light
    scene.meshes.push_back(
        testing::makeQuad(glm::vec3(-50, 0, 50), glm::vec3(100, 0, 0), glm::vec3(0, 0, -100), 0));
    scene.meshes.push_back(testing::makeQuad(glm::vec3(-half, 2 * height, -half),
                                             glm::vec3(0, 0, 2 * half), glm::vec3(2 * half, 0, 0),
                                             1));
    const float intensity = 3.0f;
    scene.punctualLights.push_back(
        pointLight("lamp", glm::vec3(0, height, 0), glm::vec3(intensity)));
    scene.render.causticPhotons = 20000;
    scene.render.indirectCausticPhotons = 0;  // only the light's photons
    scene.image = {8, 8, 0};
    InProcessRenderer r(scene);
    ASSERT_TRUE(r.renderer().builder().causticsActive());
    const LightingSet set = r.renderer().builder().build(0, 0);
    glm::dvec3 total(0.0);
    for (const auto& p : set.caustics.photons()) total += glm::dvec3(p.power);
    // Solid angle of a 2a x 2b rectangle seen from distance d on its axis.
    const double a = half, b = half, d = height;
    const double omega = 4.0 * std::asin(a * b / std::sqrt((a * a + d * d) * (b * b + d * d)));
    EXPECT_NEAR(total.x / (0.8 * intensity * omega), 1.0, 0.01);
    // Photons are aimed at the cone of the mirror's bounding sphere; those that miss the square
    // escape upward, so only part of them land, but those that do carry all the power.
    EXPECT_GT(set.caustics.photons().size(), 5000u);
    EXPECT_EQ(set.photonsShot, 20000u);

    // An accumulated frame's set gathers every set's photons, each with 1 / K of its power:
    // K times the photons, the same flux, and every set of the frame holds the same pool.
    scene.render.causticPhotons = 2000;
    InProcessRenderer pooled(scene);
    const auto& builder = pooled.renderer().builder();
    const LightingSet own = builder.build(3, 0, 4), first = builder.build(3, 5, 4),
                      second = builder.build(3, 5, 7);
    const std::size_t sets = std::size_t(scene.render.setCount());
    glm::dvec3 pooledTotal(0.0);
    for (const auto& p : first.caustics.photons()) pooledTotal += glm::dvec3(p.power);
    EXPECT_GT(first.caustics.photons().size(), (sets - 1) * own.caustics.photons().size());
    EXPECT_NEAR(pooledTotal.x / (0.8 * intensity * omega), 1.0, 0.01);
    ASSERT_EQ(first.caustics.photons().size(), second.caustics.photons().size());
    EXPECT_EQ(first.caustics.photons()[17].position, second.caustics.photons()[17].position);
    EXPECT_EQ(first.photonsShot, 2000u);  // its share of the shooting
    scene.render.poolCaustics = false;
    InProcessRenderer alone(scene);
    EXPECT_EQ(alone.renderer().builder().build(3, 5, 4).caustics.photons().size(),
              alone.renderer().builder().build(3, 0, 4).caustics.photons().size());
}

}  // namespace
}  // namespace igi
