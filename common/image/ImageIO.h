#pragma once

#include <filesystem>

#include "image/Image.h"

namespace igi {

/// Writes an image; the format follows the extension: .exr is linear float RGB, .png is
/// tone-mapped (exposure in stops, clipped, sRGB) 8-bit RGB. Creates missing parent folders.
/// Throws std::runtime_error naming the file on failure.
void writeImage(const std::filesystem::path& path, const Image& image, float exposure = 0.0f);

/// Reads any format OpenImageIO knows as linear float RGB (8-bit PNG/JPEG are decoded from
/// sRGB). Throws std::runtime_error naming the file on failure.
Image readImage(const std::filesystem::path& path);

}  // namespace igi
