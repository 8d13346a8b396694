#include "SessionScene.h"

#include <stdexcept>

#include <spdlog/spdlog.h>

#include "Animation.h"
#include "ImageSize.h"
#include "LightingReport.h"
#include "OptionWarnings.h"
#include "RenderFlags.h"
#include "scene/RenderSettingsJson.h"
#include "scene/SceneError.h"

namespace igi {

Scene loadSessionScene(const MasterOptions& options, SceneBundle& bundle) {
    SceneLoadOptions loadOptions;
    loadOptions.allowOutsidePaths = options.allowOutsidePaths;
    loadOptions.headlight = options.headlight;
    Scene scene = loadSceneFile(options.scene, &bundle, loadOptions);
    reportLighting(scene, options);
    const nlohmann::json overrides = nlohmann::json::parse(options.renderOverridesJson);
    try {
        applyRenderSettingsJson(overrides, scene.render, "command line", "/render");
    } catch (const SceneError& e) {
        throw std::invalid_argument(commandLineMessage(e));  // names the flag, not the key
    }
    for (const std::string& warning : uselessOptionWarnings(options, overrides, scene.render))
        spdlog::warn("{}", warning);
    const ImageSize size =
        overriddenImageSize({scene.image.width, scene.image.height}, options.width, options.height);
    scene.image.width = size.width;
    scene.image.height = size.height;
    if (options.exposureSet) scene.image.exposure = options.exposure;
    return scene;
}

nlohmann::json sessionJson(const MasterOptions& options, const Scene& scene) {
    const RenderSettings& s = scene.render;
    return {{"scene", options.scene.string()},
            {"width", scene.image.width},
            {"height", scene.image.height},
            {"exposure", scene.image.exposure},
            {"integrator", s.integrator == IntegratorKind::Path ? "path" : "igi"},
            {"gi", giModeName(s.gi)},
            {"seed", s.seed},
            {"frames", options.frames},
            {"animation", options.animation.string()},
            {"local_clients", options.localClients},
            {"remote_clients", options.remoteClients},
            {"render", renderSettingsJson(s)}};
}

int framesWithAnimation(const MasterOptions& options, const Animation& animation) {
    const int length = int(animation.lastKeyFrame()) + 1;
    if (!options.framesGiven) {
        // One frame of a 32-frame animation is never what was meant.
        spdlog::info("--animation {}: rendering its {} frames (0 to its last keyframe {})",
                     options.animation.string(), length, length - 1);
        return length;
    }
    if (options.frames > 0 && options.frames < length)
        spdlog::warn("--frames {} stops before the end of --animation {}: its last keyframe is {}",
                     options.frames, options.animation.string(), length - 1);
    return options.frames;
}

}  // namespace igi
