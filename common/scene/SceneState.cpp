#include "scene/SceneState.h"

#include <stdexcept>

namespace igi {

SceneState SceneState::of(const Scene& scene) {
    SceneState s;
    s.camera = scene.camera;
    for (const Mesh& m : scene.meshes) s.transforms.push_back(m.transform);
    s.materials = scene.materials;
    s.punctualLights = scene.punctualLights;
    s.quadLights = scene.quadLights;
    s.environment = scene.environment;
    s.render = scene.render;
    return s;
}

void SceneState::applyTo(Scene& scene) const {
    if (transforms.size() != scene.meshes.size() || materials.size() != scene.materials.size() ||
        punctualLights.size() != scene.punctualLights.size() ||
        quadLights.size() != scene.quadLights.size())
        throw std::invalid_argument("a scene state applied to a scene of another shape");
    scene.camera = camera;
    for (std::size_t i = 0; i < transforms.size(); ++i) scene.meshes[i].transform = transforms[i];
    scene.materials = materials;
    scene.punctualLights = punctualLights;
    scene.quadLights = quadLights;
    scene.environment = environment;
    scene.render = render;
}

}  // namespace igi
