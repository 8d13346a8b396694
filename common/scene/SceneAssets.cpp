#include "scene/SceneAssets.h"

#include <utility>

#include "scene/SceneError.h"
#include "scene/TextureLoader.h"

namespace igi {

SceneAssets::SceneAssets(FileSource& files, Scene& scene, const SceneLimits& limits)
    : files_(files),
      scene_(scene),
      limits_(limits),
      triangles_(limits.maxTriangles, "triangles", "per scene"),
      vertices_(limits.maxVertices, "vertices", "per scene"),
      texturePixels_(limits.maxTotalTexturePixels, "texture pixels", "per scene") {}

std::optional<int> SceneAssets::textureFile(const std::string& path) {
    auto cached = byKey_.find(path);
    if (cached != byKey_.end()) return cached->second;
    const std::optional<std::string> found = locateFile(files_, path);
    if (!found) return std::nullopt;
    auto cachedFound = byKey_.find(*found);
    if (cachedFound != byKey_.end()) return byKey_[path] = cachedFound->second;
    const int index = add(*found, *found, files_.read(*found));
    byKey_[path] = index;
    return index;
}

int SceneAssets::textureBytes(const std::string& key, const std::string& name,
                              const std::string& bytes, TextureEncoding encoding) {
    // One image may be both a colour and data (rarely, but a file may say so): two decodes.
    const std::string k = encoding == TextureEncoding::Data ? key + "#data" : key;
    auto cached = byKey_.find(k);
    if (cached != byKey_.end()) return cached->second;
    return add(k, name, bytes, encoding);
}

void SceneAssets::checkMaterialCount(std::size_t count, const std::string& file) const {
    const std::size_t have = scene_.materials.size();
    if (count <= limits_.maxMaterials && have <= limits_.maxMaterials - count) return;
    throw SceneError::inFile(file, std::to_string(count) +
                                       " more materials would exceed the limit of " +
                                       std::to_string(limits_.maxMaterials) + " per scene (" +
                                       std::to_string(have) + " already)");
}

int SceneAssets::add(const std::string& key, const std::string& name, const std::string& bytes,
                     TextureEncoding encoding) {
    TextureLimits textureLimits{limits_.maxTexturePixels, &texturePixels_};
    Texture texture = decodeTexture(name, bytes, textureLimits, encoding);
    const int index = static_cast<int>(scene_.textures.size());
    scene_.textures.push_back(std::move(texture));
    byKey_[key] = index;
    return index;
}

}  // namespace igi
