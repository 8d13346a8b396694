#pragma once

#include <vector>

#include "scene/Camera.h"
#include "scene/Environment.h"
#include "scene/Light.h"
#include "scene/Material.h"
#include "scene/Scene.h"
#include "scene/Transform.h"

namespace igi {

/// Everything about a scene that may change while it renders: the camera, where each object
/// is, the lights, the materials, the environment's radiance (or scale) and rotation, and the
/// settings it is rendered with (a `settings` control command changes them at a new epoch).
/// Geometry and textures (the environment's map among them) stay as loaded. The master keeps the
/// current state; each change makes a new epoch, and clients keep one state per epoch they
/// still have tiles for.
struct SceneState {
    Camera camera;
    std::vector<Transform> transforms;  ///< one per mesh, in Scene::meshes order
    std::vector<Material> materials;    ///< as Scene::materials
    std::vector<PunctualLight> punctualLights;
    std::vector<QuadLight> quadLights;
    Environment environment;
    RenderSettings render;

    /// The state a freshly loaded scene is in.
    static SceneState of(const Scene& scene);
    /// Writes this state into a scene of the same shape (same counts).
    void applyTo(Scene& scene) const;

    bool operator==(const SceneState&) const = default;
    /// Whether everything but the camera is equal: the light in the scene is the same.
    bool sameLighting(const SceneState& o) const {
        return transforms == o.transforms && sameLightsAndMaterials(o);
    }
    /// The same emitters and materials (objects may have moved): a light path that meets the
    /// same surfaces carries the same power.
    bool sameLightsAndMaterials(const SceneState& o) const {
        return materials == o.materials && punctualLights == o.punctualLights &&
               quadLights == o.quadLights && environment == o.environment;
    }
};

}  // namespace igi
