#include "LightingReport.h"

#include <spdlog/spdlog.h>

#include "scene/SceneLoader.h"

namespace igi {

void reportLighting(const Scene& scene, const MasterOptions& o) {
    if (sceneHasHeadlight(scene)) {
        const std::string ext = o.scene.extension().string();
        spdlog::info("a headlight at the camera lights the scene ({})",
                     o.headlight      ? "--headlight"
                     : ext != ".json" ? "nothing in the model emits light"
                                      : "the scene file asks for it");
    } else if (!sceneHasEmitter(scene)) {
        spdlog::warn(
            "scene {} has no light (no lights, environment or emissive material): the image "
            "will be black; --headlight adds a light at the camera",
            o.scene.string());
    }
}

}  // namespace igi
