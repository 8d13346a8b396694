#pragma once
// Whether an MTL bump map (`bump`, `map_bump`) is a height map or a normal map: the format
// does not say, and files hold both (Dabrovic Sponza's are grey heights and colour images;
// Blender's importer reads every one as a normal map).

#include "scene/Texture.h"

namespace igi {

/// Whether a bump map's image (decoded as data) reads as a tangent-space normal map: it is RGB
/// (its channels differ somewhere), its blue is above one half in at least 90 % of its texels,
/// and those texels decode (2 texel - 1) to vectors of length 1 within 25 %. The last test
/// keeps bright colour images, which some files name as bump maps (Sponza's 00_SKAP.JPG), for
/// heights: their blue is above one half too, but they are not unit vectors.
bool readsAsNormalMap(const Texture& map);

}  // namespace igi
