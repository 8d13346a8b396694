#include "lighting/CacheSites.h"

#include <cmath>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "testing/TestScenes.h"

namespace igi {
namespace {

using testing::cornellBox;
using testing::makeQuad;

// About area / spacing^2 sites, each inside its triangle, and the same sites every time.
TEST(CacheSites, DensityFollowsTheAreaAndPlacementIsAFunctionOfTheScene) {
    Scene scene;
    scene.materials = {testing::diffuse(glm::vec3(0.5f))};
    scene.meshes = {makeQuad(glm::vec3(0.0f), {2, 0, 0}, {0, 0, 3}, 0)};
    const CacheSites a = CacheSites::place(scene, 0.1f, 7, 1u << 20);
    EXPECT_NEAR(double(a.sites.size()), 600.0, 2.0);  // 6 m^2 / 0.01 m^2
    EXPECT_FLOAT_EQ(a.spacing, 0.1f);
    for (const SurfaceLightSite& s : a.sites) {
        ASSERT_GE(s.b1, 0.0f);
        ASSERT_GE(s.b2, 0.0f);
        ASSERT_LE(s.b1 + s.b2, 1.0f);
    }
    const CacheSites b = CacheSites::place(scene, 0.1f, 7, 1u << 20);
    EXPECT_EQ(a.sites, b.sites);
    // A cap on the count widens the spacing instead of leaving surfaces bare.
    const CacheSites capped = CacheSites::place(scene, 0.1f, 7, 60);
    EXPECT_LE(capped.sites.size(), 60u);
    EXPECT_NEAR(capped.spacing, std::sqrt(6.0f / 60.0f), 1e-4f);
}

// Mirrors and glass get no site: nothing diffuse is cached there.
TEST(CacheSites, NoSitesOnMirrorsAndGlass) {
    Scene scene = cornellBox(1.0f, true);
    const CacheSites sites = CacheSites::place(scene, 0.05f, 1, 1u << 20);
    const std::uint32_t ball = std::uint32_t(scene.meshes.size() - 1);
    for (const SurfaceLightSite& s : sites.sites) ASSERT_NE(s.mesh, ball);
    EXPECT_GT(sites.sites.size(), 1000u);
}

// The interpolation uses the side of a site that faces the point's way, never a site whose
// normal is turned away, nor one off the point's tangent plane (the floor under a table), and
// its weights fall to zero at the radius, so that a point that moves sees no seam.
TEST(CacheSites, InterpolationWeightsChooseSidesNormalsAndPlanes) {
    Scene scene;
    scene.materials = {testing::diffuse(glm::vec3(0.5f))};
    // A floor at y = 0 and a table top at y = 0.3 above part of it, facing up; a wall at x = 0.
    scene.meshes = {makeQuad(glm::vec3(0.0f), {0, 0, 1}, {1, 0, 0}, 0),
                    makeQuad({0.2f, 0.3f, 0.2f}, {0, 0, 0.4f}, {0.4f, 0, 0}, 0),
                    makeQuad(glm::vec3(0.0f), {0, 1, 0}, {0, 0, 1}, 0)};
    const CacheSites sites = CacheSites::place(scene, 0.05f, 3, 1u << 20);
    const SiteGrid grid(scene, SceneState::of(scene), sites, 0.1f);
    const glm::vec3 up(0, 1, 0);
    // On the floor under the table: only floor sites, every one within the radius.
    const glm::vec3 p(0.4f, 0.0f, 0.4f);
    SiteWeights w;
    interpolationWeights(grid, p, up, 0.9f, w);
    ASSERT_FALSE(w.empty());
    for (const SiteWeight& s : w) {
        const std::uint32_t site = s.record / 2;
        EXPECT_EQ(sites.sites[site].mesh, 0u);
        EXPECT_EQ(s.record % 2, 0u);  // the floor's front side faces up
        EXPECT_LE(glm::length(grid.position(site) - p), 0.1f + 1e-6f);
        EXPECT_GT(s.weight, 0.0f);
    }
    // Below the floor, facing down: the back sides of the same sites.
    SiteWeights below;
    interpolationWeights(grid, p, -up, 0.9f, below);
    ASSERT_FALSE(below.empty());
    for (const SiteWeight& s : below) EXPECT_EQ(s.record % 2, 1u);
    // Near the wall, facing up: no wall site (normals 90 degrees apart).
    SiteWeights corner;
    interpolationWeights(grid, {0.02f, 0, 0.5f}, up, 0.9f, corner);
    ASSERT_FALSE(corner.empty());
    for (const SiteWeight& s : corner) EXPECT_NE(sites.sites[s.record / 2].mesh, 2u);
    // A site at the radius's edge weighs (nearly) nothing.
    const std::uint32_t any = w.items[0].record / 2;
    const glm::vec3 away = grid.position(any) + glm::vec3(0.0999f, 0, 0);
    SiteWeights edge;
    interpolationWeights(grid, away, up, 0.9f, edge);
    for (const SiteWeight& s : edge)
        if (s.record / 2 == any) {
            EXPECT_LT(s.weight, 0.002f);
        }
}

}  // namespace
}  // namespace igi
