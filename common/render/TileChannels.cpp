#include "render/TileChannels.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace igi {

void TileChannels::resize(int n, std::uint32_t planes) {
    if (n < 0)
        throw std::invalid_argument("TileChannels::resize: negative pixel count " +
                                    std::to_string(n));
    count = n;
    // assign, not resize: every entry takes the default, whatever the planes held before.
    auto set = [&](auto& plane, Channel bit, auto value) {
        if (planes & bit)
            plane.assign(static_cast<std::size_t>(n), value);
        else
            plane.clear();
    };
    set(irradiance, kIrradiance, glm::vec3(0.0f));
    set(reflectance, kReflectance, glm::vec3(0.0f));
    set(normal, kNormal, glm::vec3(0.0f));
    set(depth, kDepth, INFINITY);
    set(unfiltered, kUnfiltered, glm::vec3(0.0f));
    set(glossy, kGlossy, glm::vec3(0.0f));
}

std::uint32_t TileChannels::mask() const {
    std::uint32_t m = 0;
    if (!irradiance.empty()) m |= kIrradiance;
    if (!reflectance.empty()) m |= kReflectance;
    if (!normal.empty()) m |= kNormal;
    if (!depth.empty()) m |= kDepth;
    if (!unfiltered.empty()) m |= kUnfiltered;
    if (!glossy.empty()) m |= kGlossy;
    return m;
}

}  // namespace igi
