#pragma once

#include <filesystem>
#include <map>
#include <string>

#include "scene/FileSource.h"
#include "scene/Scene.h"

namespace igi {

/// Everything a client needs to rebuild a scene without a shared disk: the scene file's text
/// and the bytes of every file it references, keyed by their path relative to the scene file.
struct SceneBundle {
    std::string sceneName;  ///< the scene file's name, for messages
    std::string sceneText;  ///< the JSON scene file (synthesized for a bare .obj)
    std::map<std::string, std::string> files;
};

/// Parses a JSON scene file's text, reading referenced files through `files`.
/// Throws SceneError naming the file and the line or JSON path of what is wrong.
Scene parseScene(const std::string& sceneText, const std::string& sceneName, FileSource& files);

/// Loads a .json scene file, or a bare .obj (for which it writes a scene file that frames the
/// object's bounds and adds a headlight if the OBJ has no emitter). Also returns the bundle of
/// every byte it read.
Scene loadSceneFile(const std::filesystem::path& path, SceneBundle* bundle = nullptr);

/// Rebuilds a scene from a bundle received from the master.
Scene loadSceneBundle(const SceneBundle& bundle);

}  // namespace igi
