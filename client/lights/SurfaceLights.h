#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "scene/Scene.h"
#include "scene/SceneState.h"

namespace igi {

/// Where a virtual surface-element light (VSL) of photon streaming sits (Meneveaux and
/// Bridault 2008, section 4.2): a point of one triangle of one mesh, in barycentric
/// coordinates, so that it moves with its object whatever the mesh's transform becomes.
struct SurfaceLightSite {
    std::uint32_t mesh = 0;
    std::uint32_t triangle = 0;
    float b1 = 0, b2 = 0;  ///< barycentric weights of the triangle's second and third vertices
    bool operator==(const SurfaceLightSite&) const = default;
};

/// A VSL in one scene state: world position and unit geometric normal.
struct SurfaceLight {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 0.0f, 1.0f};
};

/// Places `count` VSLs on the surfaces that reflect diffusely or glossily (no emitters, mirrors
/// or glass) of `scene` in `state`, as the paper does: area-proportional over the triangles,
/// each point drawn in its triangle shrunk by a tenth about its centroid (off edges and
/// corners), 10 % more than wanted, then the VSL closest to its nearest neighbour removed
/// until `count` remain (their Algorithm 1, which evens the spacing). A function of the
/// scene, the state and `seed` only: every client places the same VSLs. Fewer than `count`
/// when the scene has no such surface.
std::vector<SurfaceLightSite> placeSurfaceLights(const Scene& scene, const SceneState& state,
                                                 int count, std::uint64_t seed);

/// The paper's Algorithm 1: of `points`, removes the one closest to its nearest neighbour
/// until `count` remain (recomputing only the neighbours of points whose nearest it was);
/// true for the kept ones.
std::vector<bool> thinSurfaceLights(const std::vector<glm::vec3>& points, std::size_t count);

/// The sites' positions and normals with the meshes placed by `state`.
std::vector<SurfaceLight> surfaceLightsIn(const Scene& scene, const SceneState& state,
                                          const std::vector<SurfaceLightSite>& sites);

/// Which VSL a photon that met a surface at `position` (unit normal `normal`, on the side the
/// photon came from) is deposited on: the nearest whose normal is within 60 degrees of the
/// surface's either way (a photon on a floor is not deposited on the wall next to it), or the
/// nearest of all when none is; `front` tells on which side of the VSL the photon arrived (a
/// thin wall lit from both sides lights both). `lights` must not be empty.
struct SurfaceLightHit {
    std::size_t index = 0;
    bool front = true;
};
SurfaceLightHit nearestSurfaceLight(const std::vector<SurfaceLight>& lights, glm::vec3 position,
                                    glm::vec3 normal);

}  // namespace igi
