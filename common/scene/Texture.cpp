#include "scene/Texture.h"

#include <cmath>

namespace igi {

namespace {

int wrap(int i, int n) {
    int r = i % n;
    return r < 0 ? r + n : r;
}

// Bilinear lookup with wrapping in a row-major width x height image (row 0 at v = 1);
// `fallback` for coordinates that are not finite.
template <typename T>
T bilinear(const std::vector<T>& values, int width, int height, glm::vec2 uv, T fallback) {
    // Texel centres sit at half-integer coordinates; rows are stored top first while v grows
    // upwards, hence the flip.
    const float x = uv.x * static_cast<float>(width) - 0.5f;
    const float y = (1.0f - uv.y) * static_cast<float>(height) - 0.5f;
    const float fx0 = std::floor(x);
    const float fy0 = std::floor(y);
    if (!std::isfinite(fx0) || !std::isfinite(fy0)) return fallback;
    const float tx = x - fx0;
    const float ty = y - fy0;
    // Reduce before converting to int so that huge coordinates cannot overflow.
    const int x0 = static_cast<int>(std::fmod(fx0, static_cast<float>(width)));
    const int y0 = static_cast<int>(std::fmod(fy0, static_cast<float>(height)));
    const int xa = wrap(x0, width), xb = wrap(x0 + 1, width);
    const int ya = wrap(y0, height), yb = wrap(y0 + 1, height);
    auto at = [&](int px, int py) { return values[static_cast<size_t>(py) * width + px]; };
    const T top = at(xa, ya) * (1.0f - tx) + at(xb, ya) * tx;
    const T bottom = at(xa, yb) * (1.0f - tx) + at(xb, yb) * tx;
    return top * (1.0f - ty) + bottom * ty;
}

}  // namespace

glm::vec3 Texture::sample(glm::vec2 uv) const {
    if (width <= 0 || height <= 0 || texels.empty()) return glm::vec3(1.0f);
    return bilinear(texels, width, height, uv, average);
}

float Texture::sampleAlpha(glm::vec2 uv) const {
    if (width <= 0 || height <= 0 || alpha.size() != static_cast<size_t>(width) * height)
        return 1.0f;
    return bilinear(alpha, width, height, uv, alphaMinimum);
}

}  // namespace igi
