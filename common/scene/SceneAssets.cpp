#include "scene/SceneAssets.h"

#include <utility>

#include "scene/TextureLoader.h"

namespace igi {

std::optional<int> SceneAssets::textureFile(const std::string& path) {
    auto cached = byKey_.find(path);
    if (cached != byKey_.end()) return cached->second;
    const std::optional<std::string> found = locateFile(files_, path);
    if (!found) return std::nullopt;
    auto cachedFound = byKey_.find(*found);
    if (cachedFound != byKey_.end()) return byKey_[path] = cachedFound->second;
    const int index = add(*found, decodeTexture(*found, files_.read(*found)));
    byKey_[path] = index;
    return index;
}

int SceneAssets::textureBytes(const std::string& key, const std::string& name,
                              const std::string& bytes) {
    auto cached = byKey_.find(key);
    if (cached != byKey_.end()) return cached->second;
    return add(key, decodeTexture(name, bytes));
}

int SceneAssets::add(const std::string& key, Texture texture) {
    const int index = static_cast<int>(scene_.textures.size());
    scene_.textures.push_back(std::move(texture));
    byKey_[key] = index;
    return index;
}

}  // namespace igi
