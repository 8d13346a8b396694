#pragma once

// The sections of a JSON scene file, each read by its own file (CameraJson.cpp,
// LightsJson.cpp, MeshesJson.cpp, MaterialOverrides.cpp, SceneParser.cpp). Keys, types,
// ranges and defaults: docs/SCENE_FORMAT.md.

#include "scene/JsonReader.h"
#include "scene/Scene.h"
#include "scene/SceneAssets.h"
#include "scene/SceneBounds.h"
#include "scene/SceneLimits.h"

namespace igi {

/// "image": {width, height, exposure}.
ImageSettings parseImage(const JsonNode& node);

/// "camera": {position, look_at, up, fov_y}; rejects degenerate cameras.
Camera parseCamera(const JsonNode& node);

/// The camera used when a scene file has none: looks at the centre of `bounds` from +Z, far
/// enough that the bounding sphere fits a 45 degree field of view (vertically, and
/// horizontally for portrait images). Throws SceneError naming `file` when there is nothing
/// to frame.
Camera frameBounds(const Bounds3& bounds, const ImageSettings& image, const std::string& file);

/// Adds the point light at the camera that gives an irradiance of 1 at the look-at point.
void addHeadlight(Scene& scene);

/// "lights": [{type: "point" | "quad", ...}]; refuses more than `maxLights` in the scene.
void parseLights(const JsonNode& node, Scene& scene,
                 std::size_t maxLights = SceneLimits{}.maxLights);

/// "meshes": [{file, name, transform}]: loads every file into scene.meshes (and its glTF
/// lights into scene.punctualLights).
/// The "environment" section: a constant sky or an equirectangular map (its texture decoded
/// into the scene's textures; non-finite texels are an error naming the file and the texel).
void parseEnvironment(const JsonNode& node, SceneAssets& assets);

void loadMeshes(const JsonNode& node, SceneAssets& assets);

/// "materials": {name: {overrides}}, applied to every loaded material of that name.
void applyMaterialOverrides(const JsonNode& node, SceneAssets& assets);

/// A material's "type" (diffuse, glossy, mirror, glass, rough_glass, metallic_roughness): the
/// two fields it sets, `glass` and `reflection`. The scene file's overrides and the material
/// control command both read it here.
void applyMaterialType(const JsonNode& node, Material& m);

}  // namespace igi
