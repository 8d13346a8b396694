#include "scene/SceneChange.h"

#include <stdexcept>
#include <string>

namespace igi {
namespace {

template <typename T>
void checkIndex(std::uint32_t index, const std::vector<T>& items, const char* what) {
    if (index >= items.size())
        throw std::invalid_argument(std::string("a change to ") + what + " " +
                                    std::to_string(index) + " of a scene with " +
                                    std::to_string(items.size()));
}

void apply(SceneState& s, const SceneChange& change) {
    std::visit(
        [&](const auto& c) {
            using C = std::decay_t<decltype(c)>;
            if constexpr (std::is_same_v<C, CameraChange>) {
                s.camera = c.camera;
            } else if constexpr (std::is_same_v<C, TransformChange>) {
                checkIndex(c.mesh, s.transforms, "mesh");
                s.transforms[c.mesh] = c.transform;
            } else if constexpr (std::is_same_v<C, PunctualLightChange>) {
                checkIndex(c.light, s.punctualLights, "point light");
                PunctualLight value = c.value;
                value.name = s.punctualLights[c.light].name;
                s.punctualLights[c.light] = value;
            } else if constexpr (std::is_same_v<C, QuadLightChange>) {
                checkIndex(c.light, s.quadLights, "quad light");
                QuadLight value = c.value;
                value.name = s.quadLights[c.light].name;
                s.quadLights[c.light] = value;
            } else if constexpr (std::is_same_v<C, SettingsChange>) {
                s.render = c.settings;
            } else if constexpr (std::is_same_v<C, EnvironmentChange>) {
                Environment value = c.value;
                value.texture = s.environment.texture;  // the map is the scene's file
                s.environment = value;
            } else {
                checkIndex(c.material, s.materials, "material");
                Material value = c.value;
                value.name = s.materials[c.material].name;
                // Textures are the scene's files, which no change carries.
                value.diffuseTexture = s.materials[c.material].diffuseTexture;
                value.metallicRoughnessTexture = s.materials[c.material].metallicRoughnessTexture;
                // So is the normal map, and its scale with it.
                value.normalTexture = s.materials[c.material].normalTexture;
                value.normalScale = s.materials[c.material].normalScale;
                value.bumpTexture = s.materials[c.material].bumpTexture;
                value.bumpScale = s.materials[c.material].bumpScale;
                // The emissive texture too: its factor (`emission`) changes live.
                value.emissionTexture = s.materials[c.material].emissionTexture;
                // Coverage is not changed live: which triangles have filter functions is
                // fixed when the client builds its Embree geometry.
                value.alphaMode = s.materials[c.material].alphaMode;
                value.alpha = s.materials[c.material].alpha;
                value.alphaCutoff = s.materials[c.material].alphaCutoff;
                value.alphaTexture = s.materials[c.material].alphaTexture;
                // Nor are the textures' uv transforms.
                value.diffuseUv = s.materials[c.material].diffuseUv;
                value.metallicRoughnessUv = s.materials[c.material].metallicRoughnessUv;
                value.normalUv = s.materials[c.material].normalUv;
                value.alphaUv = s.materials[c.material].alphaUv;
                value.emissionUv = s.materials[c.material].emissionUv;
                s.materials[c.material] = value;
            }
        },
        change);
}

}  // namespace

void applyChanges(SceneState& state, const std::vector<SceneChange>& changes) {
    SceneState next = state;  // all or nothing
    for (const SceneChange& c : changes) apply(next, c);
    state = std::move(next);
}

bool changesSettings(const std::vector<SceneChange>& changes) {
    for (const SceneChange& c : changes)
        if (std::holds_alternative<SettingsChange>(c)) return true;
    return false;
}

std::vector<SceneChange> diffStates(const SceneState& from, const SceneState& to) {
    std::vector<SceneChange> changes;
    if (!(from.render == to.render)) changes.push_back(SettingsChange{to.render});
    if (!(from.camera == to.camera)) changes.push_back(CameraChange{to.camera});
    for (std::uint32_t i = 0; i < to.transforms.size() && i < from.transforms.size(); ++i)
        if (!(from.transforms[i] == to.transforms[i]))
            changes.push_back(TransformChange{i, to.transforms[i]});
    for (std::uint32_t i = 0; i < to.punctualLights.size() && i < from.punctualLights.size(); ++i)
        if (!(from.punctualLights[i] == to.punctualLights[i]))
            changes.push_back(PunctualLightChange{i, to.punctualLights[i]});
    for (std::uint32_t i = 0; i < to.quadLights.size() && i < from.quadLights.size(); ++i)
        if (!(from.quadLights[i] == to.quadLights[i]))
            changes.push_back(QuadLightChange{i, to.quadLights[i]});
    for (std::uint32_t i = 0; i < to.materials.size() && i < from.materials.size(); ++i)
        if (!(from.materials[i] == to.materials[i]))
            changes.push_back(MaterialChange{i, to.materials[i]});
    if (!(from.environment == to.environment)) changes.push_back(EnvironmentChange{to.environment});
    return changes;
}

}  // namespace igi
