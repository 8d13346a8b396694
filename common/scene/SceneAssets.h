#pragma once

// What the loaders of one scene share: the file source, the scene being filled, and the
// textures already decoded (so that twenty Sponza materials naming one JPEG decode it once).

#include <map>
#include <optional>
#include <string>

#include "scene/FileSource.h"
#include "scene/Scene.h"

namespace igi {

class SceneAssets {
  public:
    SceneAssets(FileSource& files, Scene& scene) : files_(files), scene_(scene) {}

    FileSource& files() { return files_; }
    Scene& scene() { return scene_; }

    /// Index in Scene::textures of the texture file at `path` (relative to the scene file),
    /// found case-insensitively if need be and decoded once; nothing when no such file exists.
    std::optional<int> textureFile(const std::string& path);

    /// Index of a texture decoded from bytes already in memory (glTF images), cached under
    /// `key`; `name` picks the decoder by its extension.
    int textureBytes(const std::string& key, const std::string& name, const std::string& bytes);

  private:
    int add(const std::string& key, Texture texture);

    FileSource& files_;
    Scene& scene_;
    std::map<std::string, int> byKey_;
};

}  // namespace igi
