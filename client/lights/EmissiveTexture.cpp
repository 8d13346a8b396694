#include "lights/EmissiveTexture.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "math/Color.h"

namespace igi {
namespace {

constexpr int kMaxGrid = 32;  // sub-triangles per edge: at most 1024 lookups a triangle
constexpr long long kMaxBoundTexels = 1 << 16;  // beyond this, the whole image's maximum
constexpr float kFloorOfBound = 1e-3f;

int wrapIndex(long long i, int n) {
    const long long r = i % n;
    return int(r < 0 ? r + n : r);
}

}  // namespace

EmissiveTexture::EmissiveTexture(const Texture& texture, const UvTransform& transform,
                                 const std::array<glm::vec2, 3>& uvs)
    : texture_(&texture) {
    // An affine transform maps the triangle's uvs to a triangle: transform the corners.
    uv0_ = transform(uvs[0]);
    du1_ = transform(uvs[1]) - uv0_;
    du2_ = transform(uvs[2]) - uv0_;
}

glm::vec3 EmissiveTexture::mean() const {
    const glm::vec2 size(float(std::max(texture_->width, 1)), float(std::max(texture_->height, 1)));
    const float longest = std::max(
        {glm::length(du1_ * size), glm::length(du2_ * size), glm::length((du2_ - du1_) * size)});
    const int k =
        std::isfinite(longest) ? std::clamp(int(std::ceil(2.0f * longest)), 1, kMaxGrid) : kMaxGrid;
    // k^2 sub-triangles of equal area: k (k + 1) / 2 upright ones and k (k - 1) / 2 upside
    // down; each counts by its centroid.
    glm::dvec3 sum(0.0);
    const float step = 1.0f / float(k);
    for (int i = 0; i < k; ++i)
        for (int j = 0; i + j < k; ++j) {
            sum +=
                glm::dvec3(at({(float(i) + 1.0f / 3.0f) * step, (float(j) + 1.0f / 3.0f) * step}));
            if (i + j + 1 < k)
                sum += glm::dvec3(
                    at({(float(i) + 2.0f / 3.0f) * step, (float(j) + 2.0f / 3.0f) * step}));
        }
    return glm::vec3(sum / double(k * k));
}

float EmissiveTexture::luminanceBound(float imageMaximum) const {
    const Texture& t = *texture_;
    if (t.width <= 0 || t.height <= 0 || !t.hasTexels()) return 1.0f;  // sample() gives 1
    const glm::vec2 a = uv0_, b = uv0_ + du1_, c = uv0_ + du2_;
    const glm::vec2 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
    // Texel coordinates as Texture::sample computes them (row 0 at v = 1), one texel around.
    const double x0 = std::floor(double(lo.x) * t.width - 0.5) - 1;
    const double x1 = std::floor(double(hi.x) * t.width - 0.5) + 2;
    const double y0 = std::floor((1.0 - double(hi.y)) * t.height - 0.5) - 1;
    const double y1 = std::floor((1.0 - double(lo.y)) * t.height - 0.5) + 2;
    const double nx = x1 - x0 + 1, ny = y1 - y0 + 1;
    // Bounds wider than the image wrap around it: texels are visited again, which is harmless.
    if (!std::isfinite(nx * ny) || nx * ny > double(kMaxBoundTexels)) return imageMaximum;
    float m = 0;
    for (long long y = (long long)y0; y <= (long long)y1; ++y)
        for (long long x = (long long)x0; x <= (long long)x1; ++x)
            m = std::max(
                m, luminance(t.texel(int(wrapIndex(x, t.width)), int(wrapIndex(y, t.height)))));
    return m;
}

float maxTexelLuminance(const Texture& texture) {
    if (texture.width <= 0 || texture.height <= 0 || !texture.hasTexels()) return 1.0f;
    float m = 0;
    for (std::size_t i = 0; i < texture.texelCount(); ++i)
        m = std::max(m, luminance(texture.texel(i)));
    return m;
}

float emittedLuminance(const EmissiveTexture& texture, glm::vec3 emission, float imageMaximum) {
    const float bound = texture.luminanceBound(imageMaximum);
    if (!(bound > 0)) return 0.0f;
    // luminance(emission x texel) <= max(emission) x luminance(texel): the floor's bound.
    return std::max(luminance(emission * texture.mean()),
                    kFloorOfBound * maxComponent(emission) * bound);
}

}  // namespace igi
