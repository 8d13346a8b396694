#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "scene/SceneError.h"
#include "scene/SceneSections.h"

namespace igi {

namespace {

constexpr float kDefaultFovDeg = 45.0f;

// Rejects the cameras from which no view can be built: no direction, no up, or an up along
// the direction (the image's roll would be undefined).
void validateCamera(const Camera& c, const JsonNode& node) {
    const glm::vec3 dir = c.lookAt - c.position;
    const float scale = std::max(glm::length(c.position), glm::length(c.lookAt));
    const float distance = glm::length(dir);
    if (!(distance > 1e-6f * scale) || !(distance > 0.0f)) {
        node.at("look_at").fail("look_at equals position: the camera has no view direction");
    }
    // "up" may be absent (the default): the error still names where to fix it.
    const auto failUp = [&](const std::string& message) {
        throw SceneError::atPath(
            node.file(), node.path() + "/up",
            node.has("up") ? message : "the default " + message + ": give 'up'");
    };
    if (!(glm::length(c.up) > 0.0f)) failUp("up is the zero vector");
    const float sine = glm::length(glm::cross(dir / distance, glm::normalize(c.up)));
    if (!(sine > 1e-4f)) failUp("up is parallel to the view direction (look_at - position)");
}

}  // namespace

ImageSettings parseImage(const JsonNode& node) {
    node.checkKeys({"width", "height", "exposure"});
    ImageSettings image;
    // Output size in pixels.
    image.width = static_cast<int>(node.at("width").integer(1, 16384));
    image.height = static_cast<int>(node.at("height").integer(1, 16384));
    // Exposure in stops (a factor of 2^exposure) applied before tone mapping.
    if (auto e = node.find("exposure")) image.exposure = e->real(NumberRange::closed(-64, 64));
    return image;
}

Camera parseCamera(const JsonNode& node) {
    node.checkKeys({"position", "look_at", "up", "fov_y"});
    Camera c;
    c.position = node.at("position").vec3();
    c.lookAt = node.at("look_at").vec3();
    if (auto up = node.find("up")) c.up = up->vec3();
    // Vertical field of view in degrees; the horizontal one follows from the image's aspect.
    c.fovYDeg = kDefaultFovDeg;
    if (auto fov = node.find("fov_y")) c.fovYDeg = fov->real(NumberRange::open(0, 180));
    validateCamera(c, node);
    return c;
}

Camera frameBounds(const Bounds3& bounds, const ImageSettings& image, const std::string& file) {
    if (bounds.empty()) {
        throw SceneError::inFile(file,
                                 "no camera given and nothing to frame (no meshes, no lights)");
    }
    const float radius = std::max(0.5f * bounds.diagonal(), 1e-3f * glm::length(bounds.centre()));
    const float halfY = glm::radians(kDefaultFovDeg) / 2.0f;
    const float aspect = static_cast<float>(image.width) / static_cast<float>(image.height);
    const float halfX = std::atan(std::tan(halfY) * aspect);
    const float half = std::min(halfX, halfY);
    Camera c;
    c.lookAt = bounds.centre();
    // A scene that is a single point still gets a usable distance.
    const float distance = (radius > 0.0f ? radius : 1.0f) / std::sin(half);
    c.position = c.lookAt + glm::vec3(0.0f, 0.0f, distance);
    c.up = glm::vec3(0.0f, 1.0f, 0.0f);
    c.fovYDeg = kDefaultFovDeg;
    return c;
}

void addHeadlight(Scene& scene) {
    // Irradiance I / d^2 at the look-at point, facing the camera: 1 when I = d^2.
    const float d = glm::length(scene.camera.position - scene.camera.lookAt);
    PunctualLight light;
    light.name = "headlight";
    light.position = scene.camera.position;
    light.intensity = glm::vec3(d * d);
    scene.punctualLights.push_back(light);
}

}  // namespace igi
