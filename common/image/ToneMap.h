#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <vector>

#include <glm/vec3.hpp>

#include "image/Image.h"

namespace igi {

/// The sRGB transfer function of a linear value in [0, 1].
inline float linearToSrgb(float v) {
    v = std::clamp(v, 0.0f, 1.0f);
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

inline float srgbToLinear(float v) {
    return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

/// Display value of a linear radiance: scaled by 2^exposure, clipped to [0, 1], sRGB-encoded,
/// 8 bits. NaN maps to 0 (never expected; the renderer's tests check there is none).
inline std::uint8_t toneMapChannel(float linear, float exposureScale) {
    const float v = linear * exposureScale;
    if (!(v > 0)) return 0;
    return static_cast<std::uint8_t>(std::lround(linearToSrgb(v) * 255.0f));
}

/// toneMapChannel of every channel, row by row, as 8-bit RGB: the PNG's bytes and the web view's.
/// The same function, bit for bit, without a pow per channel: a table of the linear values at
/// which each 8-bit level begins (toneMapChannel is monotone) answers it in a few ns.
std::vector<std::uint8_t> toneMap8(const Image& image, float exposureStops);

}  // namespace igi
