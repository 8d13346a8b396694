#pragma once

#include <string>

#include "image/Image.h"

namespace igi {

/// The image as a JPEG file in memory, tone-mapped as the PNG output is (toneMap8: exposure in
/// stops, clipped, sRGB). OpenImageIO encodes it (through an in-memory IOProxy), not our code.
/// `quality` is libjpeg's, 1-100. Throws std::runtime_error if OpenImageIO fails.
std::string encodeJpeg(const Image& image, float exposureStops, int quality = 85);

}  // namespace igi
