#pragma once
// Alpha cut-outs: glTF alphaMode MASK (alphaCutoff) and BLEND, MTL d and map_d. A hit on a
// material that can let rays through is decided where Embree finds it, by the filter functions
// of the Embree geometry that holds that material's triangles (SceneGeometry), so that eye
// rays, shadow rays, light paths and photons all see the same holes, and opaque triangles pay
// nothing. The decision is a pure function of the ray's origin and direction (as Embree hands
// them to the filter), the mesh, the triangle and the hit's barycentrics: asked twice, in a
// packet or alone, on any client, it is the same.

#include <cstdint>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "scene/Material.h"
#include "scene/Mesh.h"
#include "scene/Texture.h"

namespace igi {

/// Whether `m` can let a ray through anywhere: Mask with alpha below its cut-off somewhere,
/// Blend with alpha below one somewhere (the factor times the texture's least alpha).
bool hasCutOuts(const Material& m, const std::vector<Texture>& textures);

/// The material's alpha at `uv`: its factor times its alpha texture's there.
float alphaAt(const Material& m, const std::vector<Texture>& textures, glm::vec2 uv);

/// BLEND's uniform number in [0, 1) for a ray meeting triangle `triangle` of mesh `mesh`: a hash
/// of the bits of the ray's origin and direction and of the two indices.
float coverageRandom(glm::vec3 origin, glm::vec3 direction, std::uint32_t mesh,
                     std::uint32_t triangle);

/// Whether a hit of alpha `alpha` counts: Mask where alpha >= alphaCutoff, Blend where
/// `random` < alpha, Opaque always.
bool covers(const Material& m, float alpha, float random);

/// The cut-out triangles of one mesh: what the filter functions of their Embree geometry read.
struct CutOutTriangles {
    const Mesh* mesh = nullptr;
    std::uint32_t meshIndex = 0;
    std::int32_t material = -1;  ///< every triangle's (Mesh::material), or -1: mesh->materialIds
    std::vector<std::uint32_t> triangles;              ///< Embree primitive -> the mesh's triangle
    const std::vector<Material>* materials = nullptr;  ///< the scene's, as loaded
    const std::vector<Texture>* textures = nullptr;

    /// Whether a ray that meets primitive `prim` at barycentrics (u, v) hits it.
    bool hits(glm::vec3 origin, glm::vec3 direction, std::uint32_t prim, float u, float v) const;
};

/// The filter function (intersect and occluded alike) of a cut-out geometry whose user data is
/// its CutOutTriangles: switches off the lanes whose hit does not count.
void coverageFilter(const RTCFilterFunctionNArguments* args);

}  // namespace igi
