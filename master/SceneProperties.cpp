#include "SceneProperties.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "scene/JsonReader.h"
#include "scene/KeySuggestion.h"
#include "scene/SceneError.h"
#include "scene/SceneSections.h"

namespace igi {

namespace {

// Field blenders, instantiated per member: numbers and vectors interpolate, the rest step.
template <typename T, auto Field>
void linear(const T& a, const T& b, float t, T& out) {
    // a + (b - a) t rather than glm::mix's a (1 - t) + b t: between two equal keys it gives
    // exactly that value, so a property that does not move is not a change (a new epoch would
    // restart accumulation), and at t = 1 it is exactly b.
    const auto& from = a.*Field;
    const auto& to = b.*Field;
    out.*Field = t >= 1.0f ? to : from + (to - from) * t;
}

template <typename T, auto Field>
void step(const T& a, const T&, float, T& out) {
    out.*Field = a.*Field;
}

// Ranges as in docs/SCENE_FORMAT.md: albedos and tints are fractions, emitted power is not
// bounded above.
const NumberRange kFraction = NumberRange::closed(0, 1);
const NumberRange kNonNegative = NumberRange::atLeast(0);

// The same tests as the scene loader's camera check (CameraJson.cpp): a camera from which no
// view can be built.
std::optional<PropertyProblem> cameraProblem(const Camera& c) {
    const glm::vec3 dir = c.lookAt - c.position;
    const float scale = std::max(glm::length(c.position), glm::length(c.lookAt));
    const float distance = glm::length(dir);
    if (!(distance > 1e-6f * scale) || !(distance > 0.0f)) {
        return PropertyProblem{{"look_at", "position"},
                               "look_at equals position: the camera has no view direction"};
    }
    if (!(glm::length(c.up) > 0.0f)) return PropertyProblem{{"up"}, "up is the zero vector"};
    const float sine = glm::length(glm::cross(dir / distance, glm::normalize(c.up)));
    if (!(sine > 1e-4f)) {
        return PropertyProblem{{"up", "look_at", "position"},
                               "up is parallel to the view direction (look_at - position)"};
    }
    return std::nullopt;
}

std::optional<PropertyProblem> transformProblem(const Transform& t) {
    if (t.scale.x == 0.0f || t.scale.y == 0.0f || t.scale.z == 0.0f) {
        return PropertyProblem{{"scale"}, "scale must not be zero"};
    }
    return std::nullopt;
}

// As the scene loader's checks (LightsJson.cpp): cones that open, a sun no wider than a sky.
std::optional<PropertyProblem> punctualLightProblem(const PunctualLight& l) {
    if (!(l.outerDeg > 0.0f && l.outerDeg <= 90.0f))
        return PropertyProblem{{"outer_deg"}, "outer_deg must be in (0, 90]"};
    if (!(l.innerDeg >= 0.0f && l.innerDeg <= l.outerDeg))
        return PropertyProblem{{"inner_deg", "outer_deg"}, "inner_deg exceeds outer_deg"};
    return std::nullopt;
}

// A light's direction: normalized, never the zero vector.
void readDirection(const JsonNode& node, PunctualLight& l) {
    const glm::vec3 d = node.vec3();
    const float length = glm::length(d);
    if (!(length > 0.0f) || !std::isfinite(length))
        node.fail("direction is the zero vector: the light points nowhere");
    l.direction = d / length;
}

// Directions turn: blended linearly, then normalized (opposite keys, whose blend passes through
// zero, keep the first until the second).
void blendDirection(const PunctualLight& a, const PunctualLight& b, float t, PunctualLight& out) {
    if (t >= 1.0f || a.direction == b.direction) {
        out.direction = t >= 1.0f ? b.direction : a.direction;
        return;
    }
    const glm::vec3 d = a.direction + (b.direction - a.direction) * t;
    const float length = glm::length(d);
    out.direction = length > 1e-6f ? d / length : a.direction;
}

// As the scene loader's quad check (LightsJson.cpp): the quad must have an area.
std::optional<PropertyProblem> quadLightProblem(const QuadLight& q) {
    const float l1 = glm::length(q.edge1), l2 = glm::length(q.edge2);
    if (!(l1 > 0.0f)) return PropertyProblem{{"edge1"}, "edge is the zero vector"};
    if (!(l2 > 0.0f)) return PropertyProblem{{"edge2"}, "edge is the zero vector"};
    if (!(glm::length(glm::cross(q.edge1 / l1, q.edge2 / l2)) > 1e-6f)) {
        return PropertyProblem{{"edge2", "edge1"},
                               "edge2 is parallel to edge1: the quad has no area"};
    }
    return std::nullopt;
}

std::optional<PropertyProblem> environmentProblem(const Environment&) {
    return std::nullopt;  // every radiance >= 0 and every finite rotation is a sky
}

std::optional<PropertyProblem> materialProblem(const Material&) {
    return std::nullopt;  // diffuse + specular > 1 is scaled down, not refused
}

void readScale(const JsonNode& node, Transform& t) {
    // One number (uniform) or [x, y, z]; negative mirrors.
    t.scale = node.value().is_number() ? glm::vec3(node.real()) : node.vec3();
    if (t.scale.x == 0.0f || t.scale.y == 0.0f || t.scale.z == 0.0f) {
        node.fail("scale must not be zero");
    }
}

void readMaterialType(const JsonNode& node, Material& m) {
    applyMaterialType(node, m);
}

// The type is two fields that change together.
void stepMaterialType(const Material& a, const Material&, float, Material& out) {
    out.glass = a.glass;
    out.reflection = a.reflection;
}

// Like JsonNode::checkKeys, for a list built at run time (a kind's keys plus the caller's).
void checkKeys(const JsonNode& node, const std::vector<std::string>& allowed) {
    node.requireObject();
    for (const auto& [key, v] : node.value().items()) {
        if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
        std::string list;
        for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
        throw SceneError::atPath(
            node.file(), node.path() + "/" + jsonPointerEscape(key),
            "unknown key (expected one of: " + list + ")" + didYouMean(key, allowed));
    }
}

}  // namespace

template <typename T>
int PropertyTable<T>::indexOf(const std::string& key) const {
    for (std::size_t i = 0; i < properties.size(); ++i) {
        if (key == properties[i].key) return static_cast<int>(i);
    }
    return -1;
}

template <>
const PropertyTable<Camera>& propertyTable<Camera>() {
    using C = Camera;
    static const PropertyTable<C> table{
        "camera",
        {
            {"position", false, [](const JsonNode& n, C& c) { c.position = n.vec3(); },
             linear<C, &C::position>},
            {"look_at", false, [](const JsonNode& n, C& c) { c.lookAt = n.vec3(); },
             linear<C, &C::lookAt>},
            {"up", false, [](const JsonNode& n, C& c) { c.up = n.vec3(); }, linear<C, &C::up>},
            // Vertical field of view in degrees.
            {"fov_y", false,
             [](const JsonNode& n, C& c) { c.fovYDeg = n.real(NumberRange::open(0, 180)); },
             linear<C, &C::fovYDeg>},
        },
        cameraProblem};
    return table;
}

template <>
const PropertyTable<Transform>& propertyTable<Transform>() {
    using X = Transform;
    static const PropertyTable<X> table{
        "object",
        {
            {"translate", false, [](const JsonNode& n, X& t) { t.translate = n.vec3(); },
             linear<X, &X::translate>},
            // Degrees about X, then Y, then Z; interpolated per axis.
            {"rotate_deg", false, [](const JsonNode& n, X& t) { t.rotateDeg = n.vec3(); },
             linear<X, &X::rotateDeg>},
            {"scale", false, readScale, linear<X, &X::scale>},
        },
        transformProblem};
    return table;
}

template <>
const PropertyTable<PunctualLight>& propertyTable<PunctualLight>() {
    using L = PunctualLight;
    static const PropertyTable<L> table{
        "light",
        {
            {"position", false, [](const JsonNode& n, L& l) { l.position = n.vec3(); },
             linear<L, &L::position>},
            // Radiant intensity, W/sr per channel (point and spot lights).
            {"intensity", false, [](const JsonNode& n, L& l) { l.intensity = n.rgb(kNonNegative); },
             linear<L, &L::intensity>},
            // A directional light's irradiance, W/m^2 per channel: the same field.
            {"irradiance", false,
             [](const JsonNode& n, L& l) { l.intensity = n.rgb(kNonNegative); },
             linear<L, &L::intensity>},
            {"direction", false, readDirection, blendDirection},
            {"inner_deg", false,
             [](const JsonNode& n, L& l) { l.innerDeg = n.real(NumberRange::atLeast(0)); },
             linear<L, &L::innerDeg>},
            {"outer_deg", false,
             [](const JsonNode& n, L& l) { l.outerDeg = n.real(NumberRange::openClosed(0, 90)); },
             linear<L, &L::outerDeg>},
            {"angle_deg", false,
             [](const JsonNode& n, L& l) {
                 l.angleDeg = n.real(NumberRange::closed(0, kMaxSunAngleDeg));
             },
             linear<L, &L::angleDeg>},
            {"on", true, [](const JsonNode& n, L& l) { l.on = n.boolean(); }, step<L, &L::on>},
        },
        punctualLightProblem};
    return table;
}

template <>
const PropertyTable<QuadLight>& propertyTable<QuadLight>() {
    using L = QuadLight;
    static const PropertyTable<L> table{
        "quad light",
        {
            {"corner", false, [](const JsonNode& n, L& l) { l.corner = n.vec3(); },
             linear<L, &L::corner>},
            {"edge1", false, [](const JsonNode& n, L& l) { l.edge1 = n.vec3(); },
             linear<L, &L::edge1>},
            {"edge2", false, [](const JsonNode& n, L& l) { l.edge2 = n.vec3(); },
             linear<L, &L::edge2>},
            // Emitted radiance towards the side of cross(edge1, edge2).
            {"radiance", false, [](const JsonNode& n, L& l) { l.radiance = n.rgb(kNonNegative); },
             linear<L, &L::radiance>},
            {"on", true, [](const JsonNode& n, L& l) { l.on = n.boolean(); }, step<L, &L::on>},
        },
        quadLightProblem};
    return table;
}

template <>
const PropertyTable<Material>& propertyTable<Material>() {
    using M = Material;
    static const PropertyTable<M> table{
        "material",
        {
            {"type", true, readMaterialType, stepMaterialType},
            {"diffuse", false, [](const JsonNode& n, M& m) { m.diffuse = n.rgb(kFraction); },
             linear<M, &M::diffuse>},
            {"specular", false, [](const JsonNode& n, M& m) { m.specular = n.rgb(kFraction); },
             linear<M, &M::specular>},
            {"phong_exponent", false,
             [](const JsonNode& n, M& m) { m.phongExponent = n.real(kNonNegative); },
             linear<M, &M::phongExponent>},
            {"ior", false, [](const JsonNode& n, M& m) { m.ior = n.real(NumberRange::above(0)); },
             linear<M, &M::ior>},
            {"transmittance", false,
             [](const JsonNode& n, M& m) { m.transmittance = n.rgb(kFraction); },
             linear<M, &M::transmittance>},
            // Radiance emitted from the front side.
            {"emission", false, [](const JsonNode& n, M& m) { m.emission = n.rgb(kNonNegative); },
             linear<M, &M::emission>},
            // glTF metallic-roughness (type metallic_roughness): times the material's map.
            {"roughness", false, [](const JsonNode& n, M& m) { m.roughness = n.real(kFraction); },
             linear<M, &M::roughness>},
            {"metallic", false, [](const JsonNode& n, M& m) { m.metallic = n.real(kFraction); },
             linear<M, &M::metallic>},
        },
        materialProblem};
    return table;
}

template <>
const PropertyTable<Environment>& propertyTable<Environment>() {
    using E = Environment;
    static const PropertyTable<E> table{
        "environment",
        {
            // A constant sky's radiance, W/(m^2 sr) per channel.
            {"radiance", false, [](const JsonNode& n, E& e) { e.radiance = n.rgb(kNonNegative); },
             linear<E, &E::radiance>},
            // The factor a map's radiance is multiplied by (one number or per channel): the
            // same field, as in the scene file.
            {"scale", false, [](const JsonNode& n, E& e) { e.radiance = n.rgb(kNonNegative); },
             linear<E, &E::radiance>},
            // Degrees about +Y, right-handed.
            {"rotate_deg", false, [](const JsonNode& n, E& e) { e.rotateDeg = n.real(); },
             linear<E, &E::rotateDeg>},
        },
        environmentProblem};
    return table;
}

template <typename T>
PropertyMask applyProperties(const JsonNode& node, T& value,
                             const std::vector<std::string>& extraKeys) {
    const PropertyTable<T>& table = propertyTable<T>();
    std::vector<std::string> allowed = extraKeys;
    for (const Property<T>& p : table.properties) allowed.emplace_back(p.key);
    checkKeys(node, allowed);
    PropertyMask given = 0;
    for (std::size_t i = 0; i < table.properties.size(); ++i) {
        if (auto v = node.find(table.properties[i].key)) {
            table.properties[i].read(*v, value);
            given |= PropertyMask{1} << i;
        }
    }
    return given;
}

template <typename T>
void requireUsable(const JsonNode& node, const T& value) {
    const std::optional<PropertyProblem> problem = propertyTable<T>().problem(value);
    if (!problem) return;
    for (const char* key : problem->keys) {
        if (auto v = node.find(key)) v->fail(problem->message);
    }
    node.fail(problem->message);
}

float reflectedPeak(const Material& m) {
    if (m.glass) return 0.0f;
    const glm::vec3 total =
        m.diffuse + (m.reflection == Reflection::None ? glm::vec3(0.0f) : m.specular);
    return std::max({total.x, total.y, total.z});
}

bool scaleToConserveEnergy(Material& m) {
    const float peak = reflectedPeak(m);
    if (!(peak > 1.0f)) return false;
    m.diffuse /= peak;
    m.specular /= peak;
    return true;
}

#define IGI_PROPERTY_KIND(T)                                                   \
    template int PropertyTable<T>::indexOf(const std::string&) const;          \
    template PropertyMask applyProperties<T>(const JsonNode&, T&,              \
                                             const std::vector<std::string>&); \
    template void requireUsable<T>(const JsonNode&, const T&);

IGI_PROPERTY_KIND(Camera)
IGI_PROPERTY_KIND(Transform)
IGI_PROPERTY_KIND(PunctualLight)
IGI_PROPERTY_KIND(QuadLight)
IGI_PROPERTY_KIND(Material)
IGI_PROPERTY_KIND(Environment)

#undef IGI_PROPERTY_KIND

}  // namespace igi
