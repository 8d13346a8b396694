#include "RenderFlags.h"

#include <algorithm>

#include "scene/SceneError.h"

namespace igi {

std::string flagForRenderKey(const std::string& key) {
    if (key == "path_samples") return "--spp";
    if (key == "accumulate") return "--no-accumulate";
    std::string flag = "--" + key;
    std::replace(flag.begin(), flag.end(), '_', '-');
    return flag;
}

std::string commandLineMessage(const SceneError& error) {
    // "/render/interleave/0" -> "interleave": the flag gives the whole value.
    const std::string prefix = "/render/";
    const std::string& path = error.jsonPath();
    if (path.compare(0, prefix.size(), prefix) != 0) return error.what();
    const std::string key =
        path.substr(prefix.size(), path.find('/', prefix.size()) - prefix.size());
    return flagForRenderKey(key) + ": " + error.message();
}

}  // namespace igi
