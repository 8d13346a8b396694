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

    std::vector<Mesh>& meshes = assets.scene().meshes;
    std::vector<GltfInstances> instances;
    if (ext == ".obj") {
        // An OBJ file an earlier entry loaded is not loaded again: both are instances of the
        // first one's geometry (docs/SCENE_FORMAT.md, "Instances").
        auto first = std::find_if(meshes.begin(), meshes.end(), [&](const Mesh& m) {
            return m.file == mesh.file && m.geometryOf < 0 && m.partOf < 0;
        });
        if (first != meshes.end()) {
            first->instanced = true;
            mesh.geometryOf = std::int32_t(first - meshes.begin());
            mesh.instanced = true;
        } else {
            loadObj(mesh.file, assets, mesh);
        }
    } else {
        std::vector<PunctualLight> lights;
        loadGltf(mesh.file, assets, mesh, lights, &instances);
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
    std::size_t parts = 0;
    for (const GltfInstances& shared : instances) parts += shared.placements.size();
    if (parts > 0 && meshes.size() + 1 + parts > assets.limits().maxMeshes) {
        fileNode.fail("its " + std::to_string(parts) +
                      " instances of shared primitives would exceed the limit of " +
                      std::to_string(assets.limits().maxMeshes) + " meshes per scene");
    }
    const auto object = std::int32_t(meshes.size());
    meshes.push_back(std::move(mesh));
    // The glTF primitives that several nodes place: a part of this object per placement, the
    // first holding the geometry.
    for (GltfInstances& shared : instances) {
        const auto holder = std::int32_t(meshes.size());
        for (std::size_t k = 0; k < shared.placements.size(); ++k) {
            Mesh part;
            if (k == 0) part = std::move(shared.geometry);
            part.name = meshes[object].name;
            part.file = meshes[object].file;
            part.transform = meshes[object].transform;
            part.geometryOf = k == 0 ? -1 : holder;
            part.partOf = object;
            part.material = std::int32_t(shared.placements[k].material);
            part.local = shared.placements[k].matrix;
            part.instanced = true;
            meshes.push_back(std::move(part));
        }
    }
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
