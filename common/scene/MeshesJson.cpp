#include <algorithm>
#include <cctype>
#include <filesystem>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "scene/GltfLoader.h"
#include "scene/ObjLoader.h"
#include "scene/SceneError.h"
#include "scene/SceneSections.h"

namespace igi {

namespace {

std::string lowerExtension(const std::string& file) {
    std::string ext = std::filesystem::path(file).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

Transform parseTransform(const JsonNode& node) {
    node.checkKeys({"translate", "rotate_deg", "scale"});
    Transform t;
    if (auto v = node.find("translate")) t.translate = v->vec3();
    // Degrees about X, then Y, then Z.
    if (auto v = node.find("rotate_deg")) t.rotateDeg = v->vec3();
    // One number (uniform) or [x, y, z]; negative mirrors (and flips the front side).
    if (auto v = node.find("scale")) {
        t.scale = v->value().is_number() ? glm::vec3(v->real()) : v->vec3();
        if (t.scale.x == 0.0f || t.scale.y == 0.0f || t.scale.z == 0.0f) {
            v->fail("scale must not be zero");
        }
    }
    return t;
}

void loadMesh(const JsonNode& entry, SceneAssets& assets) {
    entry.checkKeys({"file", "name", "transform"});
    const JsonNode fileNode = entry.at("file");
    const std::string written = fileNode.string();
    Mesh mesh;
    // Relative to the scene file.
    mesh.file = resolveRelative("", written);
    mesh.name = std::filesystem::path(written).stem().string();
    if (auto n = entry.find("name")) mesh.name = n->string();
    if (auto t = entry.find("transform")) mesh.transform = parseTransform(*t);

    const std::string ext = lowerExtension(mesh.file);
    if (ext != ".obj" && ext != ".gltf" && ext != ".glb") {
        fileNode.fail("unsupported mesh format '" + ext + "' (expected .obj, .gltf or .glb)");
    }
    try {
        assets.files().checkPath(mesh.file);
    } catch (const SceneError& e) {
        fileNode.fail(e.message());
    }
    if (!assets.files().exists(mesh.file)) fileNode.fail("file '" + written + "' not found");

    if (ext == ".obj") {
        loadObj(mesh.file, assets, mesh);
    } else {
        std::vector<PunctualLight> lights;
        loadGltf(mesh.file, assets, mesh, lights);
        const std::size_t have = assets.scene().punctualLights.size();
        const std::size_t max = assets.limits().maxLights;
        if (lights.size() > max || have > max - lights.size()) {
            fileNode.fail("its " + std::to_string(lights.size()) +
                          " lights would exceed the limit of " + std::to_string(max) +
                          " lights per scene");
        }
        const glm::mat4 m = mesh.transform.matrix();
        for (PunctualLight& l : lights) {
            l.position = glm::vec3(m * glm::vec4(l.position, 1.0f));
            // A direction turns with the entry (its scale does not stretch the light).
            const glm::vec3 d = glm::vec3(m * glm::vec4(l.direction, 0.0f));
            if (glm::length(d) > 0.0f) l.direction = glm::normalize(d);
            assets.scene().punctualLights.push_back(std::move(l));
        }
    }
    assets.scene().meshes.push_back(std::move(mesh));
}

}  // namespace

void loadMeshes(const JsonNode& node, SceneAssets& assets) {
    if (node.value().is_array() && node.value().size() > assets.limits().maxMeshes) {
        node.fail(std::to_string(node.value().size()) + " meshes, over the limit of " +
                  std::to_string(assets.limits().maxMeshes));
    }
    for (const JsonNode& entry : node.elements()) loadMesh(entry, assets);
}

}  // namespace igi
