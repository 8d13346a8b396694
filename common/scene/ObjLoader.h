#pragma once

#include <string>

#include "scene/Mesh.h"
#include "scene/SceneAssets.h"

namespace igi {

/// Loads a Wavefront OBJ file (path relative to the scene file) into `mesh`: triangulated,
/// de-indexed to per-vertex positions, normals and uvs. Its MTL materials are appended to the
/// scene's (never merged with another file's), faces without one get defaultMaterial(), and
/// textures are decoded through `assets`. Throws SceneError naming the OBJ or MTL file and the
/// line for a missing material, library or texture, a non-finite number or a bad index.
void loadObj(const std::string& objPath, SceneAssets& assets, Mesh& mesh);

}  // namespace igi
