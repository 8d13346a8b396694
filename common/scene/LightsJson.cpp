#include <glm/geometric.hpp>

#include "scene/SceneSections.h"

namespace igi {

namespace {

PointLight parsePointLight(const JsonNode& node, std::string name) {
    node.checkKeys({"type", "name", "position", "intensity"});
    PointLight light;
    light.name = std::move(name);
    light.position = node.at("position").vec3();
    // Radiant intensity in W/sr per channel, [r, g, b] or one number.
    light.intensity = node.at("intensity").rgb(NumberRange::atLeast(0));
    return light;
}

QuadLight parseQuadLight(const JsonNode& node, std::string name) {
    node.checkKeys({"type", "name", "corner", "edge1", "edge2", "radiance"});
    QuadLight light;
    light.name = std::move(name);
    light.corner = node.at("corner").vec3();
    light.edge1 = node.at("edge1").vec3();
    light.edge2 = node.at("edge2").vec3();
    // Emitted radiance (W/(m^2 sr) per channel) towards the side of cross(edge1, edge2).
    light.radiance = node.at("radiance").rgb(NumberRange::atLeast(0));
    const float l1 = glm::length(light.edge1), l2 = glm::length(light.edge2);
    if (!(l1 > 0.0f)) node.at("edge1").fail("edge is the zero vector");
    if (!(l2 > 0.0f)) node.at("edge2").fail("edge is the zero vector");
    if (!(glm::length(glm::cross(light.edge1 / l1, light.edge2 / l2)) > 1e-6f)) {
        node.at("edge2").fail("edge2 is parallel to edge1: the quad has no area");
    }
    return light;
}

}  // namespace

void parseLights(const JsonNode& node, Scene& scene, std::size_t maxLights) {
    // glTF files may have brought lights already.
    const std::size_t have = scene.pointLights.size() + scene.quadLights.size();
    const std::size_t count = node.value().is_array() ? node.value().size() : 0;
    if (count > maxLights || have > maxLights - count) {
        node.fail(std::to_string(count) + " lights would exceed the limit of " +
                  std::to_string(maxLights) + " per scene (" + std::to_string(have) +
                  " from glTF files)");
    }
    const auto lights = node.elements();
    for (std::size_t i = 0; i < lights.size(); ++i) {
        const JsonNode& l = lights[i];
        l.requireObject();
        std::string name = "light" + std::to_string(i);
        if (auto n = l.find("name")) name = n->string();
        if (l.at("type").choice({"point", "quad"}) == "point") {
            scene.pointLights.push_back(parsePointLight(l, std::move(name)));
        } else {
            scene.quadLights.push_back(parseQuadLight(l, std::move(name)));
        }
    }
}

}  // namespace igi
