#include "SceneNames.h"

#include <algorithm>

#include "scene/JsonReader.h"

namespace igi {

namespace {

// "a, b, c" of the names a scene has, shortened for scenes with many.
std::string listNames(const std::vector<std::string>& names) {
    constexpr std::size_t kShown = 12;
    std::string list;
    for (std::size_t i = 0; i < names.size() && i < kShown; ++i) {
        list += (i == 0 ? "" : ", ") + names[i];
    }
    if (names.size() > kShown) list += ", ... (" + std::to_string(names.size()) + " in all)";
    return list.empty() ? "none" : list;
}

// Each name once, in scene order (several OBJ files may each have a "white").
template <typename Items>
std::vector<std::string> namesOf(const Items& items) {
    std::vector<std::string> names;
    for (const auto& item : items) {
        if (std::find(names.begin(), names.end(), item.name) == names.end()) {
            names.push_back(item.name);
        }
    }
    return names;
}

template <typename Items>
std::vector<std::uint32_t> indicesOf(const Items& items, const std::string& name) {
    std::vector<std::uint32_t> out;
    for (std::size_t i = 0; i < items.size(); ++i) {
        if (items[i].name == name) out.push_back(static_cast<std::uint32_t>(i));
    }
    return out;
}

// The meshes that are objects (scene-file entries), not parts of one (instances of a glTF
// file's shared primitives, which carry their object's name and follow its transform).
std::vector<std::uint32_t> objectsNamed(const std::vector<Mesh>& meshes, const std::string& name) {
    std::vector<std::uint32_t> out;
    for (std::uint32_t i : indicesOf(meshes, name))
        if (meshes[i].partOf < 0) out.push_back(i);
    return out;
}

}  // namespace

std::uint32_t SceneNames::mesh(const std::string& name, const JsonNode& where) const {
    const std::vector<std::uint32_t> found = objectsNamed(scene_.meshes, name);
    if (found.empty()) {
        where.fail("no mesh named '" + name +
                   "' (the scene's meshes: " + listNames(namesOf(scene_.meshes)) + ")");
    }
    if (found.size() > 1) {
        where.fail(std::to_string(found.size()) + " meshes are named '" + name +
                   "': give them distinct names in the scene file");
    }
    return found.front();
}

SceneNames::LightRef SceneNames::light(const std::string& name, const JsonNode& where) const {
    const std::vector<std::uint32_t> points = indicesOf(scene_.punctualLights, name);
    const std::vector<std::uint32_t> quads = indicesOf(scene_.quadLights, name);
    if (points.empty() && quads.empty()) {
        std::vector<std::string> all = namesOf(scene_.quadLights);
        for (const std::string& n : namesOf(scene_.punctualLights)) all.push_back(n);
        where.fail("no light named '" + name + "' (the scene's lights: " + listNames(all) + ")");
    }
    if (points.size() + quads.size() > 1) {
        where.fail(std::to_string(points.size() + quads.size()) + " lights are named '" + name +
                   "': give them distinct names in the scene file");
    }
    return quads.empty() ? LightRef{false, points.front()} : LightRef{true, quads.front()};
}

std::vector<std::uint32_t> SceneNames::materials(const std::string& name,
                                                 const JsonNode& where) const {
    std::vector<std::uint32_t> found = indicesOf(scene_.materials, name);
    if (found.empty()) {
        where.fail("no material named '" + name +
                   "' (the scene's materials: " + listNames(namesOf(scene_.materials)) + ")");
    }
    return found;
}

}  // namespace igi
