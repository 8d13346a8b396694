#pragma once

#include <filesystem>
#include <map>
#include <string>

#include "scene/FileSource.h"
#include "scene/Scene.h"
#include "scene/SceneLimits.h"

namespace igi {

/// Everything a client needs to rebuild a scene without a shared disk: the scene file's text
/// and the bytes of every file it references, keyed by their path relative to the scene file.
struct SceneBundle {
    std::string sceneName;  ///< the scene file's name, for messages
    std::string sceneText;  ///< the JSON scene file (synthesized for a bare .obj)
    std::map<std::string, std::string> files;
};

/// Parses a JSON scene file's text, reading referenced files through `files`, within `limits`.
/// Throws SceneError naming the file and the line or JSON path of what is wrong.
Scene parseScene(const std::string& sceneText, const std::string& sceneName, FileSource& files,
                 const SceneLimits& limits = {});

/// Loads a .json scene file, or a bare .obj (for which it writes a scene file that frames the
/// object's bounds and adds a headlight if the OBJ has no emitter). Also returns the bundle of
/// every byte it read. The scene file's folder bounds what it may reference unless
/// options.allowOutsidePaths (a bare OBJ's folder bounds its MTL files and textures). When a
/// bundle is asked for, its file names are checked as a client will check them, so that a
/// scene a client would refuse fails here first.
Scene loadSceneFile(const std::filesystem::path& path, SceneBundle* bundle = nullptr,
                    const SceneLoadOptions& options = {});
/// The same, without the bundle.
Scene loadSceneFile(const std::filesystem::path& path, const SceneLoadOptions& options);

/// Whether anything in the scene gives light: a light, an environment or an emissive material.
bool sceneHasEmitter(const Scene& scene);
/// Whether the scene has the headlight that "headlight": true (or a bare model without an
/// emitter, or SceneLoadOptions::headlight) adds at the camera.
bool sceneHasHeadlight(const Scene& scene);

/// Rebuilds a scene from a bundle received from the master. Refuses file names that are
/// empty, absolute or contain a NUL byte, and anything beyond `limits`.
Scene loadSceneBundle(const SceneBundle& bundle, const SceneLimits& limits = {});

}  // namespace igi
