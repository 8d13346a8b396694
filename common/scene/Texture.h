#pragma once

#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace igi {

/// How a lookup outside [0, 1] continues the image, per axis: a glTF sampler's wrapS / wrapT
/// (REPEAT, CLAMP_TO_EDGE, MIRRORED_REPEAT). OBJ / MTL textures repeat.
enum class TextureWrap { Repeat, ClampToEdge, MirroredRepeat };

/// A decoded colour texture in linear RGB.
struct Texture {
    std::string path;  ///< as the referencing file named it, for messages
    int width = 0;
    int height = 0;
    std::vector<glm::vec3> texels;  ///< row-major; row 0 is the top of the image (v = 1)
    glm::vec3 average{0.0f};        ///< mean texel, used for the scene's mean albedo
    glm::vec3 minimum{0.0f};        ///< per channel: bounds a roughness map's sharpest lobe
    /// The first texel (row-major index) whose file value was not finite, or -1; such values
    /// are read as 0, and an environment map refuses them (EnvironmentJson.cpp).
    long long firstNonFinite = -1;
    float nonFiniteValue = 0.0f;  ///< its value
    /// Coverage in [0, 1], row-major as texels: the image's alpha channel (never sRGB-decoded),
    /// or for TextureEncoding::Coverage without one its grey; empty when every value is 1.
    std::vector<float> alpha;
    float alphaMinimum = 1.0f;                ///< the least value of `alpha` (1 when it is empty)
    TextureWrap wrapU = TextureWrap::Repeat;  ///< along u (glTF's S)
    TextureWrap wrapV = TextureWrap::Repeat;  ///< along v (glTF's T)

    /// Bilinear lookup, continued outside [0, 1] by wrapU and wrapV; (u, v) as in OBJ, v = 0 at
    /// the bottom.
    glm::vec3 sample(glm::vec2 uv) const;
    /// The same for `alpha`: 1 when the texture has none.
    float sampleAlpha(glm::vec2 uv) const;
};

}  // namespace igi
