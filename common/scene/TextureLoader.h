#pragma once

// Decoding texture files (with OpenImageIO, from bytes read through a FileSource) and the
// case-insensitive lookup that real scenes need (Sponza's MTL says 00_SKAP.JPG, the file is
// 00_skap.JPG).

#include <cstdint>
#include <optional>
#include <string>

#include "scene/FileSource.h"
#include "scene/SceneLimits.h"
#include "scene/Texture.h"

namespace igi {

/// How large an image decodeTexture accepts, judged from its header before any pixel is read.
struct TextureLimits {
    std::uint64_t maxPixels = SceneLimits{}.maxTexturePixels;
    /// The scene's texture pixels so far, charged with this image's (nullptr: not counted).
    Budget* scenePixels = nullptr;
};

/// How an integer image's values map to linear ones.
enum class TextureEncoding {
    Colour,  ///< sRGB-encoded unless the file says it is linear (colours: base colour, Kd)
    Data,    ///< the values themselves (glTF metallicRoughnessTexture, normal maps)
    /// As Data, and a coverage map: Texture::alpha is the alpha channel, or the grey of an
    /// image without one (MTL map_d).
    Coverage,
};

/// Decodes an image into linear RGB. Integer images (8- or 16-bit) are taken as sRGB-encoded
/// unless the file says it is linear or `encoding` is Data; float images are linear. Grey images
/// are replicated to RGB. An alpha channel (not premultiplied into the colours) becomes
/// Texture::alpha when some value is below one. `name` (its extension) picks the decoder and names
/// the texture. Throws SceneError naming `name` when the bytes are not a readable image, or when
/// its header claims more pixels than `limits` allow (then no pixel memory is allocated).
Texture decodeTexture(const std::string& name, const std::string& bytes,
                      const TextureLimits& limits = {},
                      TextureEncoding encoding = TextureEncoding::Colour);

/// `path` itself when it exists; else the one file in the same folder whose name equals it
/// ignoring case (logged as a warning naming both); else nothing.
std::optional<std::string> locateFile(FileSource& files, const std::string& path);

}  // namespace igi
