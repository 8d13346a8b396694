// loadSceneFile and loadSceneBundle: where the bytes come from (disk or a bundle) and how a
// bare mesh file (OBJ, glTF, GLB) becomes a scene file.

#include "scene/SceneLoader.h"

#include <algorithm>
#include <cctype>

#include <nlohmann/json.hpp>

#include "scene/SceneError.h"
#include "scene/SceneSections.h"

namespace igi {

namespace {

namespace fs = std::filesystem;

std::string lowerExtension(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

std::string readSceneText(const fs::path& path, const SceneLimits& limits) {
    return readRegularFile(path, limits.maxSceneFileBytes, path.string());
}

// The scene file a bare mesh file stands for: the object, auto-framed, lit by a headlight when
// it has no emitter of its own.
std::string meshSceneText(const std::string& meshName, bool headlight) {
    nlohmann::ordered_json scene;
    scene["meshes"] = nlohmann::ordered_json::array({{{"file", meshName}}});
    if (headlight) scene["headlight"] = true;
    return scene.dump(2) + "\n";
}

// Errors name files relative to the scene file's folder; the user typed a path relative to
// their working directory, so report it that way.
SceneError relativeToUser(const SceneError& e, const fs::path& folder) {
    const std::string file = fs::path(e.file()).is_absolute()
                                 ? e.file()
                                 : (folder / e.file()).lexically_normal().string();
    return SceneError(file, e.line(), e.jsonPath(), e.message());
}

Scene loadFromDisk(const fs::path& path, SceneBundle& bundle, const SceneLoadOptions& options) {
    const std::string name = path.filename().string();
    DiskFileSource disk(path.parent_path(), options);
    Scene scene;
    const std::string ext = lowerExtension(path);
    if (ext == ".json") {
        bundle.sceneText = readSceneText(path, options.limits);
        scene = parseScene(bundle.sceneText, name, disk, options.limits);
    } else if (ext == ".obj" || ext == ".gltf" || ext == ".glb") {
        bundle.sceneText = meshSceneText(name, false);
        scene = parseScene(bundle.sceneText, name, disk, options.limits);
        // The headlight depends on the materials, known only now: add it as parseScene would
        // for the text that says so, and ship that text.
        if (!sceneHasEmitter(scene)) {
            bundle.sceneText = meshSceneText(name, true);
            addHeadlight(scene);
        }
    } else {
        throw SceneError::inFile(path.string(), "unsupported scene file type '" + ext +
                                                    "' (expected .json, .obj, .gltf or .glb)");
    }
    if (options.headlight && !sceneHasHeadlight(scene)) {
        // Said in the text the clients parse, so that each adds the same light, last, as
        // parseScene does for "headlight": true.
        nlohmann::ordered_json text = nlohmann::ordered_json::parse(bundle.sceneText);
        text["headlight"] = true;
        bundle.sceneText = text.dump(2) + "\n";
        addHeadlight(scene);
    }
    bundle.sceneName = name;
    bundle.files = disk.filesRead();
    return scene;
}

}  // namespace

bool sceneHasEmitter(const Scene& scene) {
    if (!scene.quadLights.empty() || !scene.punctualLights.empty() || scene.environment.present())
        return true;
    return std::any_of(scene.materials.begin(), scene.materials.end(),
                       [](const Material& m) { return m.isEmissive(); });
}

bool sceneHasHeadlight(const Scene& scene) {
    return std::any_of(scene.punctualLights.begin(), scene.punctualLights.end(),
                       [](const PunctualLight& l) { return l.name == "headlight"; });
}

Scene loadSceneFile(const std::filesystem::path& path, SceneBundle* bundle,
                    const SceneLoadOptions& options) {
    SceneBundle local;
    SceneBundle& out = bundle ? *bundle : local;
    try {
        Scene scene = loadFromDisk(path, out, options);
        // Allowed outside paths may be absolute, which no client accepts: say so here.
        if (bundle) {
            for (const auto& [name, bytes] : out.files) checkBundlePath(name);
        }
        scene.sourcePath = path.string();
        return scene;
    } catch (const SceneError& e) {
        if (e.file() == path.string()) throw;
        throw relativeToUser(e, path.parent_path());
    }
}

Scene loadSceneFile(const std::filesystem::path& path, const SceneLoadOptions& options) {
    return loadSceneFile(path, nullptr, options);
}

Scene loadSceneBundle(const SceneBundle& bundle, const SceneLimits& limits) {
    if (bundle.sceneText.size() > limits.maxSceneFileBytes) {
        throw SceneError::inFile(bundle.sceneName,
                                 "scene file is " + std::to_string(bundle.sceneText.size()) +
                                     " bytes, over the limit of " +
                                     std::to_string(limits.maxSceneFileBytes) + " bytes");
    }
    for (const auto& [name, bytes] : bundle.files) {
        checkBundlePath(name);
        if (bytes.size() > limits.maxFileBytes) {
            throw SceneError::inFile(name, "file is " + std::to_string(bytes.size()) +
                                               " bytes, over the limit of " +
                                               std::to_string(limits.maxFileBytes) + " bytes");
        }
    }
    BundleFileSource files(bundle.files);
    return parseScene(bundle.sceneText, bundle.sceneName, files, limits);
}

}  // namespace igi
