#pragma once

#include <string>
#include <vector>

#include "scene/Light.h"
#include "scene/Mesh.h"
#include "scene/SceneAssets.h"

namespace igi {

/// Loads a glTF 2.0 file (.gltf with its buffers and images, or .glb; path relative to the
/// scene file) into `mesh`: every node of the default scene flattened into one triangle mesh
/// with the node transforms baked in. Its materials are appended to the scene's (mapping in
/// docs/SCENE_FORMAT.md) and KHR_lights_punctual point lights are appended to `lights`, placed
/// in the file's space (the caller applies the mesh's own transform). Throws SceneError naming
/// the file and the glTF JSON path of what is wrong.
void loadGltf(const std::string& path, SceneAssets& assets, Mesh& mesh,
              std::vector<PunctualLight>& lights);

}  // namespace igi
