#include <cmath>

#include <glm/geometric.hpp>

#include "scene/SceneSections.h"

namespace igi {

namespace {

// A spot light's outer half-angle: a cone that opens, at most a hemisphere.
const NumberRange kOuterConeRange = NumberRange::openClosed(0, 90);

PunctualLight parsePointLight(const JsonNode& node, std::string name) {
    node.checkKeys({"type", "name", "position", "intensity"});
    PunctualLight light;
    light.name = std::move(name);
    light.position = node.at("position").vec3();
    // Radiant intensity in W/sr per channel, [r, g, b] or one number.
    light.intensity = node.at("intensity").rgb(NumberRange::atLeast(0));
    return light;
}

// A unit direction from a key that must not be the zero vector (or non-finite).
glm::vec3 readDirection(const JsonNode& node) {
    const glm::vec3 d = node.vec3();
    const float length = glm::length(d);
    if (!(length > 0.0f) || !std::isfinite(length)) {
        node.fail("direction is the zero vector: the light points nowhere");
    }
    return d / length;
}

PunctualLight parseSpotLight(const JsonNode& node, std::string name) {
    node.checkKeys(
        {"type", "name", "position", "direction", "intensity", "inner_deg", "outer_deg"});
    PunctualLight light;
    light.name = std::move(name);
    light.kind = LightKind::Spot;
    light.position = node.at("position").vec3();
    light.direction = readDirection(node.at("direction"));
    // Radiant intensity on the axis, W/sr per channel.
    light.intensity = node.at("intensity").rgb(NumberRange::atLeast(0));
    // Half-angles of the cones, as glTF's innerConeAngle and outerConeAngle (in degrees).
    if (auto outer = node.find("outer_deg")) light.outerDeg = outer->real(kOuterConeRange);
    if (auto inner = node.find("inner_deg")) {
        light.innerDeg = inner->real(NumberRange::atLeast(0));
        if (!(light.innerDeg <= light.outerDeg)) {
            inner->fail("inner_deg " + std::to_string(light.innerDeg) + " exceeds outer_deg " +
                        std::to_string(light.outerDeg));
        }
    }
    return light;
}

PunctualLight parseDirectionalLight(const JsonNode& node, std::string name) {
    node.checkKeys({"type", "name", "direction", "irradiance", "angle_deg"});
    PunctualLight light;
    light.name = std::move(name);
    light.kind = LightKind::Directional;
    light.direction = readDirection(node.at("direction"));
    // Irradiance in W/m^2 on a surface that faces the light, per channel.
    light.intensity = node.at("irradiance").rgb(NumberRange::atLeast(0));
    if (auto angle = node.find("angle_deg"))
        light.angleDeg = angle->real(NumberRange::closed(0, kMaxSunAngleDeg));
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
    const std::size_t have = scene.punctualLights.size() + scene.quadLights.size();
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
        const std::string type = l.at("type").choice({"point", "spot", "directional", "quad"});
        if (type == "point") {
            scene.punctualLights.push_back(parsePointLight(l, std::move(name)));
        } else if (type == "spot") {
            scene.punctualLights.push_back(parseSpotLight(l, std::move(name)));
        } else if (type == "directional") {
            scene.punctualLights.push_back(parseDirectionalLight(l, std::move(name)));
        } else {
            scene.quadLights.push_back(parseQuadLight(l, std::move(name)));
        }
    }
}

}  // namespace igi
