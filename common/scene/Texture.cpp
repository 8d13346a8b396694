#include "scene/Texture.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace igi {

namespace {

int wrap(int i, int n) {
    // Within one period either side of it, as reduce() leaves most lookups: no division (an
    // integer division per texel index was a visible part of the Sponza scenes' lookups).
    if (i >= 0 && i < n) return i;
    if (i < 0 && i >= -n) return i + n;
    if (i >= n && i - n < n) return i - n;
    int r = i % n;
    return r < 0 ? r + n : r;
}

// fmod(f, period), which is f itself wherever |f| < period (most lookups): no division there.
float reduceToPeriod(float f, float period) {
    return std::fabs(f) < period ? f : std::fmod(f, period);
}

// A texel coordinate (the floor of a lookup's) brought near the image before it becomes an int,
// so that huge coordinates cannot overflow, keeping what `mode` makes of it.
float reduce(float f, int n, TextureWrap mode) {
    switch (mode) {
        case TextureWrap::ClampToEdge:
            return std::clamp(f, -1.0f, static_cast<float>(n));
        case TextureWrap::MirroredRepeat:
            return reduceToPeriod(f, 2.0f * static_cast<float>(n));  // the period of a mirror
        case TextureWrap::Repeat:
            break;
    }
    return reduceToPeriod(f, static_cast<float>(n));
}

// Texel index i (reduced) in [0, n), as `mode` continues the image past its edges.
int texelIndex(int i, int n, TextureWrap mode) {
    switch (mode) {
        case TextureWrap::ClampToEdge:
            return std::clamp(i, 0, n - 1);
        case TextureWrap::MirroredRepeat: {
            const int r = wrap(i, 2 * n);
            return r < n ? r : 2 * n - 1 - r;
        }
        case TextureWrap::Repeat:
            break;
    }
    return wrap(i, n);
}

// The four texels a bilinear lookup at uv reads in a width x height image (row 0 at v = 1),
// continued past its edges by wrapU and wrapV, and its weights; nothing for coordinates that
// are not finite.
struct Footprint {
    int xa, xb, ya, yb;
    float tx, ty;
};

std::optional<Footprint> footprintOf(glm::vec2 uv, int width, int height, TextureWrap wrapU,
                                     TextureWrap wrapV) {
    // Texel centres sit at half-integer coordinates; rows are stored top first while v grows
    // upwards, hence the flip.
    const float x = uv.x * static_cast<float>(width) - 0.5f;
    const float y = (1.0f - uv.y) * static_cast<float>(height) - 0.5f;
    const float fx0 = std::floor(x);
    const float fy0 = std::floor(y);
    if (!std::isfinite(fx0) || !std::isfinite(fy0)) return std::nullopt;
    const int x0 = static_cast<int>(reduce(fx0, width, wrapU));
    const int y0 = static_cast<int>(reduce(fy0, height, wrapV));
    return Footprint{texelIndex(x0, width, wrapU),
                     texelIndex(x0 + 1, width, wrapU),
                     texelIndex(y0, height, wrapV),
                     texelIndex(y0 + 1, height, wrapV),
                     x - fx0,
                     y - fy0};
}

// Bilinear lookup: `at(x, y)` is texel (x, y), row 0 at the top; `fallback` for coordinates
// that are not finite.
template <typename T, typename At>
T bilinear(At at, int width, int height, glm::vec2 uv, TextureWrap wrapU, TextureWrap wrapV,
           T fallback) {
    const std::optional<Footprint> f = footprintOf(uv, width, height, wrapU, wrapV);
    if (!f) return fallback;
    const float tx = f->tx, ty = f->ty;
    const T top = at(f->xa, f->ya) * (1.0f - tx) + at(f->xb, f->ya) * tx;
    const T bottom = at(f->xa, f->yb) * (1.0f - tx) + at(f->xb, f->yb) * tx;
    return top * (1.0f - ty) + bottom * ty;
}

}  // namespace

void Texture::prefetch(glm::vec2 uv) const {
    if (width <= 0 || height <= 0 || (codes.empty() && texels.empty())) return;
    const std::optional<Footprint> f = footprintOf(uv, width, height, wrapU, wrapV);
    if (!f) return;
    // The lookup's first texel; the others are mostly in the same cache line (codes' 4 x 4
    // blocks) or the next row (texels).
    if (!codes.empty()) {
        __builtin_prefetch(&codes[codeIndex(f->xa, f->ya)]);
    } else {
        __builtin_prefetch(&texels[static_cast<size_t>(f->ya) * width + f->xa]);
        __builtin_prefetch(&texels[static_cast<size_t>(f->yb) * width + f->xa]);
    }
}

glm::vec3 Texture::sample(glm::vec2 uv) const {
    if (width <= 0 || height <= 0) return glm::vec3(1.0f);
    if (!texels.empty())
        return bilinear([&](int x, int y) { return texels[static_cast<size_t>(y) * width + x]; },
                        width, height, uv, wrapU, wrapV, average);
    if (codes.empty() || table == nullptr) return glm::vec3(1.0f);
    return bilinear([&](int x, int y) { return texel(x, y); }, width, height, uv, wrapU, wrapV,
                    average);
}

float Texture::sampleAlpha(glm::vec2 uv) const {
    if (width <= 0 || height <= 0 || alpha.size() != static_cast<size_t>(width) * height)
        return 1.0f;
    return bilinear([&](int x, int y) { return alpha[static_cast<size_t>(y) * width + x]; }, width,
                    height, uv, wrapU, wrapV, alphaMinimum);
}

}  // namespace igi
