#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "render/RenderSettings.h"
#include "scene/Camera.h"
#include "scene/Environment.h"
#include "scene/Light.h"
#include "scene/Material.h"
#include "scene/Mesh.h"
#include "scene/Texture.h"

namespace igi {

/// The output image's size and how it is shown.
struct ImageSettings {
    int width = 640;
    int height = 480;
    float exposure = 0.0f;  ///< stops applied before tone mapping to the PNG
};

/// A whole scene as plain data: what a scene file says, with every mesh and texture it
/// references loaded. It knows nothing of Embree; the client turns it into a traceable scene.
struct Scene {
    std::string sourcePath;  ///< the scene file, for messages
    Camera camera;
    ImageSettings image;
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<Mesh> meshes;
    std::vector<PunctualLight> punctualLights;
    std::vector<QuadLight> quadLights;
    Environment environment;
    RenderSettings render;
};

/// The mesh holding mesh i's vertices and triangles (itself unless it is an instance).
inline const Mesh& geometryOf(const Scene& scene, std::size_t i) {
    const Mesh& m = scene.meshes[i];
    return m.geometryOf >= 0 ? scene.meshes[std::size_t(m.geometryOf)] : m;
}
/// The object (scene-file entry) mesh i belongs to: the index whose transform places it.
inline std::uint32_t objectOf(const Scene& scene, std::size_t i) {
    const Mesh& m = scene.meshes[i];
    return std::uint32_t(m.partOf >= 0 ? std::size_t(m.partOf) : i);
}
/// Mesh i's object-to-world matrix when the objects stand as `transforms` says (one per mesh,
/// SceneState::transforms): its object's transform, then (for an instance) its own placement.
inline glm::mat4 meshToWorld(const Scene& scene, const std::vector<Transform>& transforms,
                             std::size_t i) {
    const Mesh& m = scene.meshes[i];
    if (!m.instanced) return transforms[i].matrix();
    return transforms[objectOf(scene, i)].matrix() * m.local;
}
/// The material of triangle t of mesh i.
inline std::uint32_t materialOf(const Scene& scene, std::size_t i, std::uint32_t t) {
    const Mesh& m = scene.meshes[i];
    return m.material >= 0 ? std::uint32_t(m.material) : geometryOf(scene, i).materialIds[t];
}

}  // namespace igi
