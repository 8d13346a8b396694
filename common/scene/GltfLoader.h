#pragma once

#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

#include "scene/Light.h"
#include "scene/Mesh.h"
#include "scene/SceneAssets.h"

namespace igi {

/// A glTF primitive placed by several nodes (docs/SCENE_FORMAT.md, "Instances").
struct GltfInstances {
    Mesh geometry;  ///< its triangles in the primitive's own space
    struct Placement {
        glm::mat4 matrix;        ///< the node's, into the file's space
        std::uint32_t material;  ///< index into Scene::materials
    };
    std::vector<Placement> placements;
};

/// Loads a glTF 2.0 file (.gltf with its buffers and images, or .glb; path relative to the
/// scene file) into `mesh`: every node of the default scene flattened into one triangle mesh
/// with the node transforms baked in. Its materials are appended to the scene's (mapping in
/// docs/SCENE_FORMAT.md) and KHR_lights_punctual point lights are appended to `lights`, placed
/// in the file's space (the caller applies the mesh's own transform). Throws SceneError naming
/// the file and the glTF JSON path of what is wrong.
/// Given `instances`, a primitive (the same accessors) that several nodes place, each with a
/// matrix that does not mirror and an opaque material, is not flattened: it becomes one entry
/// there, its triangles once in its own space and each node's matrix and material.
void loadGltf(const std::string& path, SceneAssets& assets, Mesh& mesh,
              std::vector<PunctualLight>& lights, std::vector<GltfInstances>* instances = nullptr);

}  // namespace igi
