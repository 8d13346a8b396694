#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene/Scene.h"

namespace igi {

class JsonNode;

/// Resolves the names that animation files and control commands use to the scene's indices.
/// Each failure throws SceneError at `where` (the JSON value that named it) saying what is
/// wrong and what the scene has.
class SceneNames {
  public:
    explicit SceneNames(const Scene& scene) : scene_(scene) {}

    /// The one mesh of that name (Mesh::name); two meshes of the same name are an error.
    std::uint32_t mesh(const std::string& name, const JsonNode& where) const;

    struct LightRef {
        bool quad = false;  ///< else a point light
        std::uint32_t index = 0;
    };
    /// The one point or quad light of that name; two lights of the same name are an error.
    LightRef light(const std::string& name, const JsonNode& where) const;

    /// Every material of that name (several OBJ files may each have a "white"); at least one.
    std::vector<std::uint32_t> materials(const std::string& name, const JsonNode& where) const;

  private:
    const Scene& scene_;
};

}  // namespace igi
