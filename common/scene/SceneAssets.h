#pragma once

// What the loaders of one scene share: the file source, the scene being filled, the textures
// already decoded (so that twenty Sponza materials naming one JPEG decode it once), and the
// scene's running totals against its SceneLimits.

#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "scene/FileSource.h"
#include "scene/Scene.h"
#include "scene/SceneLimits.h"
#include "scene/TextureLoader.h"

namespace igi {

class SceneAssets {
  public:
    SceneAssets(FileSource& files, Scene& scene, const SceneLimits& limits = {});

    FileSource& files() { return files_; }
    Scene& scene() { return scene_; }
    const SceneLimits& limits() const { return limits_; }

    /// Index in Scene::textures of the texture file at `path` (relative to the scene file),
    /// found case-insensitively if need be and decoded once per encoding; nothing when no such
    /// file exists.
    std::optional<int> textureFile(const std::string& path,
                                   TextureEncoding encoding = TextureEncoding::Colour);

    /// Index of a texture decoded from bytes already in memory (glTF images), cached under
    /// `key`; `name` picks the decoder by its extension. `wrapU`, `wrapV`: how lookups continue
    /// past its edges (a glTF sampler's); an image used with two samplers is two textures.
    int textureBytes(const std::string& key, const std::string& name, const std::string& bytes,
                     TextureEncoding encoding = TextureEncoding::Colour,
                     TextureWrap wrapU = TextureWrap::Repeat,
                     TextureWrap wrapV = TextureWrap::Repeat);

    /// The scene's triangles and vertices so far: a loader checks fits() and add()s before it
    /// allocates for a file or a primitive.
    Budget& triangles() { return triangles_; }
    Budget& vertices() { return vertices_; }

    /// Throws SceneError naming `file` when `count` more materials would exceed the limit.
    void checkMaterialCount(std::size_t count, const std::string& file) const;

  private:
    int add(const std::string& key, const std::string& name, const std::string& bytes,
            TextureEncoding encoding = TextureEncoding::Colour);

    FileSource& files_;
    Scene& scene_;
    SceneLimits limits_;
    Budget triangles_;
    Budget vertices_;
    Budget texturePixels_;
    std::map<std::string, int> byKey_;
};

}  // namespace igi
