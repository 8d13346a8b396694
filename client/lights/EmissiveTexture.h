#pragma once
// An emissive texture over one light triangle (glTF emissiveTexture): what light sampling
// draws there and how much the triangle emits in all, so that a light sample, a light path's
// start and what a ray that hits the triangle sees are the same radiance.

#include <array>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "scene/Material.h"
#include "scene/Texture.h"

namespace igi {

/// The texture of one emissive triangle, in the triangle's barycentrics: b = (0, 0), (1, 0),
/// (0, 1) are its corners p0, p1, p2, as Lights' triangle samples and a hit's (u, v) are.
class EmissiveTexture {
  public:
    EmissiveTexture() = default;
    /// `uvs` at the corners, looked up through `transform` (the slot's KHR_texture_transform).
    EmissiveTexture(const Texture& texture, const UvTransform& transform,
                    const std::array<glm::vec2, 3>& uvs);

    bool present() const { return texture_ != nullptr; }
    /// The texel (bilinear) at barycentrics b: the factor on the material's emission there.
    glm::vec3 at(glm::vec2 b) const { return texture_->sample(uv0_ + b.x * du1_ + b.y * du2_); }

    /// The texel's mean over the triangle's area, integrated on a grid of equal sub-triangles
    /// at least two per texel along the longest edge (at most 32 x 32 of them): what the
    /// triangle's power is chosen by.
    glm::vec3 mean() const;
    /// The largest luminance the triangle can show: the brightest texel within its uv bounds
    /// and one texel around them (bilinear lookups blend only those), or `imageMaximum` (the
    /// whole image's, maxTexelLuminance) when the bounds are large. 0 means that the triangle
    /// emits nothing anywhere.
    float luminanceBound(float imageMaximum) const;

  private:
    const Texture* texture_ = nullptr;
    glm::vec2 uv0_{0.0f}, du1_{0.0f}, du2_{0.0f};  ///< transformed uvs: uv0 + b.x du1 + b.y du2
};

/// The luminance of a texture's brightest texel (1 for a texture without texels, which
/// Texture::sample reads as 1).
float maxTexelLuminance(const Texture& texture);

/// The luminance by which Lights chooses a textured triangle, per unit of area: that of the
/// material's `emission` times the texture's mean over it, but never below 1e-3 of its bound
/// where the bound is positive, so that no part that emits has a zero density (the grid can
/// miss a small bright spot; the estimator stays unbiased, since a sample's radiance is the
/// texel's wherever the point falls). 0 when every texel the triangle can show is black.
/// `imageMaximum` is maxTexelLuminance of its texture.
float emittedLuminance(const EmissiveTexture& texture, glm::vec3 emission, float imageMaximum);

}  // namespace igi
