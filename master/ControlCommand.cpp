#include "ControlCommand.h"

#include <spdlog/spdlog.h>

#include "SceneNames.h"
#include "SceneProperties.h"
#include "SettingsCommand.h"
#include "scene/JsonReader.h"
#include "scene/SceneError.h"

namespace igi {

namespace {

// Keys every change command has besides the properties.
const std::vector<std::string> kCameraKeys = {"cmd"};
const std::vector<std::string> kNamedKeys = {"cmd", "name"};

// `current` with the command's properties applied; a command that gives none is refused
// rather than making a change that changes nothing.
template <typename T>
T changed(const JsonNode& command, const T& current, const std::vector<std::string>& extraKeys) {
    T value = current;
    if (applyProperties(command, value, extraKeys) == 0) {
        std::string list;
        for (const Property<T>& p : propertyTable<T>().properties) {
            list += (list.empty() ? "" : ", ") + std::string(p.key);
        }
        command.fail("the command changes nothing (give one of: " + list + ")");
    }
    requireUsable(command, value);
    return value;
}

std::string nameOf(const JsonNode& command) {
    const JsonNode name = command.at("name");
    return name.string();
}

SceneChange cameraChange(const JsonNode& command, const SceneState& current) {
    return CameraChange{changed(command, current.camera, kCameraKeys)};
}

SceneChange objectChange(const JsonNode& command, const Scene& scene, const SceneState& current) {
    const std::uint32_t mesh = SceneNames(scene).mesh(nameOf(command), command.at("name"));
    return TransformChange{mesh, changed(command, current.transforms.at(mesh), kNamedKeys)};
}

SceneChange lightChange(const JsonNode& command, const Scene& scene, const SceneState& current) {
    const SceneNames::LightRef light = SceneNames(scene).light(nameOf(command), command.at("name"));
    if (light.quad) {
        return QuadLightChange{light.index,
                               changed(command, current.quadLights.at(light.index), kNamedKeys)};
    }
    return PunctualLightChange{
        light.index, changed(command, current.punctualLights.at(light.index), kNamedKeys)};
}

SceneChange environmentChange(const JsonNode& command, const SceneState& current) {
    return EnvironmentChange{changed(command, current.environment, kCameraKeys)};
}

// Every material of the name changes; each keeps its own values for what is not given.
std::vector<SceneChange> materialChanges(const JsonNode& command, const Scene& scene,
                                         const SceneState& current,
                                         std::vector<std::string>& warnings) {
    const std::string name = nameOf(command);
    std::vector<SceneChange> changes;
    bool warned = false;
    for (std::uint32_t i : SceneNames(scene).materials(name, command.at("name"))) {
        Material value = changed(command, current.materials.at(i), kNamedKeys);
        // As the scene loader does with material overrides: scale down, with a warning.
        if (scaleToConserveEnergy(value) && !warned) {
            warnings.push_back("material '" + name +
                               "': diffuse + specular reflects more than all the light: scaled "
                               "down");
            spdlog::warn("{}: {}", kControlCommandFile, warnings.back());
            warned = true;
        }
        changes.push_back(MaterialChange{i, value});
    }
    return changes;
}

}  // namespace

ControlRequest parseControlCommand(const std::string& line, const Scene& scene,
                                   const SceneState& current) {
    const nlohmann::json json = parseJsonText(line, kControlCommandFile);
    const JsonNode command(json, kControlCommandFile, "");
    command.requireObject();
    const std::string cmd = command.at("cmd").choice({"camera", "object", "light", "material",
                                                      "environment", "settings", "status", "scene",
                                                      "pick", "exposure", "snapshot", "stop"});

    ControlRequest request;
    request.kind = ControlRequest::Kind::Change;
    if (cmd == "camera") {
        request.changes.push_back(cameraChange(command, current));
    } else if (cmd == "object") {
        request.changes.push_back(objectChange(command, scene, current));
    } else if (cmd == "light") {
        request.changes.push_back(lightChange(command, scene, current));
    } else if (cmd == "material") {
        request.changes = materialChanges(command, scene, current, request.warnings);
    } else if (cmd == "environment") {
        request.changes.push_back(environmentChange(command, current));
    } else if (cmd == "settings") {
        SettingsRequest settings = settingsRequest(command, current.render);
        if (settings.change) request.changes.push_back(*settings.change);
        request.targetError = settings.targetError;
    } else if (cmd == "snapshot") {
        command.checkKeys({"cmd", "path"});
        request.kind = ControlRequest::Kind::Snapshot;
        if (auto path = command.find("path")) {
            request.path = path->string();
            if (request.path.empty()) path->fail("the path is empty");
        }
    } else if (cmd == "pick") {
        command.checkKeys({"cmd", "x", "y"});
        request.kind = ControlRequest::Kind::Pick;
        const ImageSettings& image = scene.image;
        request.x = command.at("x").real(NumberRange::closed(0, image.width));
        request.y = command.at("y").real(NumberRange::closed(0, image.height));
    } else if (cmd == "exposure") {
        command.checkKeys({"cmd", "stops"});
        request.kind = ControlRequest::Kind::Exposure;
        request.exposure =
            command.at("stops").real(NumberRange::closed(-kMaxExposureStops, kMaxExposureStops));
    } else {
        command.checkKeys({"cmd"});
        request.kind = cmd == "status"  ? ControlRequest::Kind::Status
                       : cmd == "scene" ? ControlRequest::Kind::Scene
                                        : ControlRequest::Kind::Stop;
    }
    return request;
}

}  // namespace igi
