#include "scene/BumpMapKind.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace igi {
namespace {

constexpr double kBlueAboveHalf = 0.9;  // of the texels
constexpr float kUnitTolerance = 0.25f;
constexpr float kGrey = 1.0f / 255.0f;  // channels closer than this are one grey

bool isGrey(glm::vec3 t) {
    return std::abs(t.x - t.y) < kGrey && std::abs(t.y - t.z) < kGrey;
}

}  // namespace

bool readsAsNormalMap(const Texture& map) {
    if (!map.hasTexels()) return false;
    std::size_t normal = 0;
    bool rgb = false;
    for (std::size_t i = 0; i < map.texelCount(); ++i) {
        const glm::vec3 t = map.texel(i);
        rgb = rgb || !isGrey(t);
        if (!(t.z > 0.5f)) continue;
        const float length = glm::length(2.0f * t - 1.0f);
        if (std::abs(length - 1.0f) <= kUnitTolerance) ++normal;
    }
    return rgb && double(normal) >= kBlueAboveHalf * double(map.texelCount());
}

}  // namespace igi
