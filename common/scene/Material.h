#pragma once

#include <cstdint>
#include <string>

#include <glm/mat2x2.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace igi {

/// How a material reflects specularly, besides its Lambertian part.
enum class Reflection : std::uint8_t {
    None,    ///< purely diffuse
    Glossy,  ///< a Phong lobe of weight `specular` and exponent `phongExponent`
    Mirror,  ///< perfect mirror of reflectance `specular`
    /// glTF 2.0 metallic-roughness (its Appendix B): a GGX lobe of alpha = roughness^2 with
    /// Schlick Fresnel of f0 = mix(((ior - 1) / (ior + 1))^2, base colour, metallic), over a
    /// Lambertian lobe of the base colour times (1 - metallic)(1 - f0 of the dielectric). The
    /// base colour is `diffuse` times its texture; roughness and metallic are the factors times
    /// the green and blue of `metallicRoughnessTexture`. On glass (`glass`): rough glass, the
    /// GGX BSDF of its interface (reflection and refraction, Walter et al. 2007) of alpha =
    /// roughness^2, smooth glass where alpha is below kMinGgxAlpha.
    Ggx,
};

/// How a material covers its surface: glTF's alphaMode; MTL's `d` and `map_d` are Blend. A
/// material that can let a ray through anywhere (client/tracing/AlphaCoverage.h, hasCutOuts) is
/// traced in Embree geometry of its own whose filter functions decide, per hit, whether it counts.
enum class AlphaMode : std::uint8_t {
    Opaque,  ///< every hit counts; alpha is ignored
    Mask,    ///< a hit counts where alpha >= alphaCutoff
    Blend,   ///< a hit counts with probability alpha, by a hash of the ray (stochastic coverage)
};

/// A texture slot's uv transform (glTF KHR_texture_transform), in igi's uvs (v up the image):
/// uv' = linear * uv + offset where `active`, uv itself otherwise (so that a material without
/// one computes exactly what it did before).
struct UvTransform {
    glm::mat2 linear{1.0f};
    glm::vec2 offset{0.0f};
    bool active = false;

    glm::vec2 operator()(glm::vec2 uv) const { return active ? linear * uv + offset : uv; }
    bool operator==(const UvTransform&) const = default;
};

/// Below this alpha = roughness^2 a GGX lobe is rendered as a mirror: D and V lose every bit
/// of precision in float, and no sampler finds so sharp a peak by evaluation.
constexpr float kMinGgxAlpha = 1e-3f;

/// A surface material as plain data. The renderer interprets it as up to three BSDF
/// components: Lambertian (`diffuse`), specular reflection (`reflection`) and, for glass, a
/// dielectric interface (Fresnel reflection and refraction) that replaces the other two.
struct Material {
    std::string name;
    glm::vec3 diffuse{0.8f};   ///< Kd: Lambertian albedo, multiplied by the texture when present
    int diffuseTexture = -1;   ///< index into Scene::textures, or -1
    glm::vec3 specular{0.0f};  ///< Ks: mirror reflectance, or the weight of the glossy lobe
    float phongExponent = 0;   ///< Ns, for Reflection::Glossy
    Reflection reflection = Reflection::None;
    bool glass = false;             ///< dielectric: diffuse and specular are ignored
    float ior = 1.5f;               ///< Ni, index of refraction of glass
    glm::vec3 transmittance{1.0f};  ///< tint of light refracted through glass
    /// Ke: radiance emitted on the front (counter-clockwise) side, times `emissionTexture`.
    glm::vec3 emission{0.0f};
    /// glTF emissiveTexture (sRGB), or -1: the radiance at a point is `emission` times its
    /// texel there (bilinear), for what is seen, what light sampling draws and where light
    /// paths start alike (client/lights/EmissiveTexture.h). Not changed live.
    int emissionTexture = -1;
    float roughness = 1.0f;             ///< Reflection::Ggx: perceptual roughness in [0, 1]
    float metallic = 0.0f;              ///< Reflection::Ggx: in [0, 1]
    int metallicRoughnessTexture = -1;  ///< linear: green scales roughness, blue metallic
    /// A tangent-space normal map (glTF normalTexture, linear, OpenGL convention: green toward
    /// +v), or -1. The shading normal is the frame of the tangent, bitangent and interpolated
    /// normal applied to (2 texel - 1) with x and y scaled by `normalScale`
    /// (client/materials/NormalMap.h).
    int normalTexture = -1;
    float normalScale = 1.0f;  ///< glTF normalTexture.scale
    /// A height map (MTL `bump` / `map_bump`, linear, the mean of its channels), or -1: the
    /// shading normal tilts by its slope in texture space, times `bumpScale` (MTL `-bm`):
    /// client/materials/BumpMap.h. An RGB map that reads as a normal map becomes normalTexture
    /// instead (common/scene/BumpMapKind.h).
    int bumpTexture = -1;
    float bumpScale = 1.0f;
    /// Coverage: alpha is `alpha` times the texture's (Texture::alpha) at the hit. Read when
    /// the scene loads and never changed live (SceneChange keeps them).
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alpha = 1.0f;        ///< glTF baseColorFactor's alpha, MTL d (1 - Tr)
    float alphaCutoff = 0.5f;  ///< AlphaMode::Mask: glTF alphaCutoff
    int alphaTexture = -1;     ///< texture whose Texture::alpha multiplies `alpha`, or -1
    /// Where each texture is looked up (glTF KHR_texture_transform of its slot; the alpha
    /// texture is glTF's base colour texture, with its transform). Not changed live.
    UvTransform diffuseUv, metallicRoughnessUv, normalUv, alphaUv, emissionUv;

    bool operator==(const Material&) const = default;

    bool isEmissive() const { return emission.x > 0 || emission.y > 0 || emission.z > 0; }
    /// Whether a normal or bump map changes the shading normal.
    bool perturbsNormal() const { return normalTexture >= 0 || bumpTexture >= 0; }
    /// Mirrors and glass: surfaces on which no diffuse VPL is stored and at which caustic
    /// photons are aimed.
    bool isSpecular() const {
        return glass || reflection == Reflection::Mirror ||
               (reflection == Reflection::Ggx && roughness * roughness < kMinGgxAlpha);
    }
};

}  // namespace igi
