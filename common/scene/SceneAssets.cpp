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

namespace {

// The cache key of an image decoded with `encoding`: one image may be both a colour and data
// (rarely, but a file may say so), or a colour and a coverage map: one decode each.
std::string keyOf(const std::string& key, TextureEncoding encoding) {
    switch (encoding) {
        case TextureEncoding::Data:
            return key + "#data";
        case TextureEncoding::Coverage:
            return key + "#coverage";
        default:
            return key;
    }
}

}  // namespace

std::optional<int> SceneAssets::textureFile(const std::string& path, TextureEncoding encoding) {
    auto cached = byKey_.find(keyOf(path, encoding));
    if (cached != byKey_.end()) return cached->second;
    const std::optional<std::string> found = locateFile(files_, path);
    if (!found) return std::nullopt;
    auto cachedFound = byKey_.find(keyOf(*found, encoding));
    if (cachedFound != byKey_.end()) return byKey_[keyOf(path, encoding)] = cachedFound->second;
    const int index = add(keyOf(*found, encoding), *found, files_.read(*found), encoding);
    byKey_[keyOf(path, encoding)] = index;
    return index;
}

int SceneAssets::textureBytes(const std::string& key, const std::string& name,
                              const std::string& bytes, TextureEncoding encoding, TextureWrap wrapU,
                              TextureWrap wrapV) {
    std::string k = keyOf(key, encoding);
    if (wrapU != TextureWrap::Repeat || wrapV != TextureWrap::Repeat)
        k += "#wrap" + std::to_string(int(wrapU)) + std::to_string(int(wrapV));
    auto cached = byKey_.find(k);
    if (cached != byKey_.end()) return cached->second;
    const int index = add(k, name, bytes, encoding);
    scene_.textures[std::size_t(index)].wrapU = wrapU;
    scene_.textures[std::size_t(index)].wrapV = wrapV;
    return index;
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
