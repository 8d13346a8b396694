#pragma once

// Decoding texture files (with OpenImageIO, from bytes read through a FileSource) and the
// case-insensitive lookup that real scenes need (Sponza's MTL says 00_SKAP.JPG, the file is
// 00_skap.JPG).

#include <optional>
#include <string>

#include "scene/FileSource.h"
#include "scene/Texture.h"

namespace igi {

/// Decodes an image into linear RGB. Integer images (8- or 16-bit) are taken as sRGB-encoded
/// unless the file says it is linear; float images are linear. Grey images are replicated to
/// RGB, alpha is dropped. `name` (its extension) picks the decoder and names the texture.
/// Throws SceneError naming `name` when the bytes are not a readable image.
Texture decodeTexture(const std::string& name, const std::string& bytes);

/// `path` itself when it exists; else the one file in the same folder whose name equals it
/// ignoring case (logged as a warning naming both); else nothing.
std::optional<std::string> locateFile(FileSource& files, const std::string& path);

}  // namespace igi
