// parseScene: reads a JSON scene file's sections in dependency order.

#include "scene/RenderSettingsJson.h"
#include "scene/SceneBounds.h"
#include "scene/SceneError.h"
#include "scene/SceneLoader.h"
#include "scene/SceneSections.h"

namespace igi {

Scene parseScene(const std::string& sceneText, const std::string& sceneName, FileSource& files,
                 const SceneLimits& limits) {
    if (sceneText.size() > limits.maxSceneFileBytes) {
        throw SceneError::inFile(sceneName, "scene file is " + std::to_string(sceneText.size()) +
                                                " bytes, over the limit of " +
                                                std::to_string(limits.maxSceneFileBytes) +
                                                " bytes");
    }
    const nlohmann::json json = parseJsonText(sceneText, sceneName);
    const JsonNode root(json, sceneName, "");
    root.checkKeys(
        {"camera", "image", "meshes", "lights", "environment", "materials", "render", "headlight"});

    Scene scene;
    scene.sourcePath = sceneName;
    SceneAssets assets(files, scene, limits);
    if (auto n = root.find("image")) scene.image = parseImage(*n);
    // Meshes first: material overrides name their materials, the default camera frames them.
    if (auto n = root.find("meshes")) loadMeshes(*n, assets);
    if (auto n = root.find("materials")) applyMaterialOverrides(*n, assets);
    if (auto n = root.find("lights")) parseLights(*n, scene, limits.maxLights);
    if (auto n = root.find("environment")) parseEnvironment(*n, assets);
    if (auto n = root.find("render"))
        applyRenderSettingsJson(n->value(), scene.render, sceneName, n->path());
    if (auto n = root.find("camera")) {
        scene.camera = parseCamera(*n);
    } else {
        scene.camera = frameBounds(worldBounds(scene), scene.image, sceneName);
    }
    // For scenes without emitters (bare OBJs): a light at the eye, so something is visible.
    if (auto n = root.find("headlight"); n && n->boolean()) addHeadlight(scene);
    return scene;
}

}  // namespace igi
