#pragma once
// Height maps (MTL `bump` / `map_bump` with `-bm`) as a tangent-space normal: the map's slope in
// texture space, by central differences one texel apart. The result goes through the same
// tangent frame and below-surface fix as a normal map's (NormalMap.h).

#include <algorithm>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "scene/Texture.h"

namespace igi::bumpmap {

/// A texel's height: the mean of its channels (a grey map's grey; a colour image used as a bump
/// map, as Dabrovic Sponza's are, by its brightness).
inline float height(glm::vec3 texel) {
    return (texel.x + texel.y + texel.z) / 3.0f;
}

/// The tangent-space normal (+x toward +u, +y toward +v, +z along the normal; not unit) of the
/// height map at uv: (-scale dh/du, -scale dh/dv, 1) with the slopes in height per texel, so that
/// a rise of 1 / scale over one texel tilts the normal by 45 degrees. Per texel rather than per
/// unit of length on the surface: the image then does not depend on the scene's scale (a scene
/// scaled by 1e3 renders the same), and it is what height-to-normal-map converters compute.
inline glm::vec3 tangentSpaceNormal(const Texture& map, glm::vec2 uv, float scale) {
    const glm::vec2 du(1.0f / float(std::max(map.width, 1)), 0.0f);
    const glm::vec2 dv(0.0f, 1.0f / float(std::max(map.height, 1)));
    const float slopeU = 0.5f * (height(map.sample(uv + du)) - height(map.sample(uv - du)));
    const float slopeV = 0.5f * (height(map.sample(uv + dv)) - height(map.sample(uv - dv)));
    return {-scale * slopeU, -scale * slopeV, 1.0f};
}

}  // namespace igi::bumpmap
