#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
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
    /// Row-major, row 0 at the top of the image (v = 1): the texels of an image that is not
    /// 8-bit (float, half, 16-bit), or of one made in code; empty when `codes` holds the image.
    std::vector<glm::vec3> texels;
    /// An 8-bit image: per texel its red, green and blue codes (bytes 0, 1, 2; byte 3 unused),
    /// each decoded through `table`, laid out in tiles (codeIndex). A lookup in a large image
    /// waits on memory, not on arithmetic: on Sponza a third of the client's time went to such
    /// waits. A quarter of the float texels' memory, and tiles of 4 x 4 texels in one cache line
    /// and 32 x 32 in one 4 KB page, so that a bilinear lookup and its neighbours (a bump map's
    /// four, the next pixel's) mostly share lines and pages where rows would not. Decoding
    /// through the table gives the very floats the float path would have stored. An image
    /// narrower or lower than a tile keeps its rows (tilesX 0): tiles would pad a 1 x 32768
    /// strip to 32 times its texels, and a hostile scene could claim many such strips.
    std::vector<std::uint32_t> codes;
    const std::array<float, 256>* table = nullptr;  ///< code -> linear value, for `codes`
    int tilesX = 0;  ///< 32 x 32 tiles per row of `codes` (the width rounded up, / 32); 0: rows
    glm::vec3 average{0.0f};  ///< mean texel, used for the scene's mean albedo
    glm::vec3 minimum{0.0f};  ///< per channel: bounds a roughness map's sharpest lobe
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

    /// Whether the image has texels (in `texels` or in `codes`); a lookup in one without
    /// gives 1.
    bool hasTexels() const { return !texels.empty() || (!codes.empty() && table != nullptr); }
    /// Number of texels held (width x height when hasTexels()).
    std::size_t texelCount() const {
        return texels.empty() ? (codes.empty() ? 0 : std::size_t(width) * std::size_t(height))
                              : texels.size();
    }
    /// Where texel (x, y) is in `codes`: 32 x 32 tiles, row by row; in a tile, 4 x 4 blocks
    /// (64 bytes) row by row; in a block, texels row by row. Without tiles, rows.
    std::size_t codeIndex(int x, int y) const {
        if (tilesX == 0) return std::size_t(y) * std::size_t(width) + std::size_t(x);
        const std::size_t tile = std::size_t(y >> 5) * std::size_t(tilesX) + std::size_t(x >> 5);
        const unsigned inTile = unsigned((y >> 2) & 7) << 7 | unsigned((x >> 2) & 7) << 4 |
                                unsigned(y & 3) << 2 | unsigned(x & 3);
        return tile << 10 | inTile;
    }
    /// Texel (x, y), row 0 at the top, whichever way it is held.
    glm::vec3 texel(int x, int y) const {
        if (!texels.empty()) return texels[std::size_t(y) * std::size_t(width) + std::size_t(x)];
        const std::uint32_t c = codes[codeIndex(x, y)];
        const std::array<float, 256>& t = *table;
        return {t[c & 0xffu], t[(c >> 8) & 0xffu], t[(c >> 16) & 0xffu]};
    }
    /// Texel i, counted row by row from the top left.
    glm::vec3 texel(std::size_t i) const {
        if (!texels.empty()) return texels[i];
        return texel(int(i % std::size_t(width)), int(i / std::size_t(width)));
    }

    /// Bilinear lookup, continued outside [0, 1] by wrapU and wrapV; (u, v) as in OBJ, v = 0 at
    /// the bottom.
    glm::vec3 sample(glm::vec2 uv) const;
    /// Asks the memory for the texels that sample(uv) reads (a hint: no effect on any value).
    void prefetch(glm::vec2 uv) const;
    /// The same for `alpha`: 1 when the texture has none.
    float sampleAlpha(glm::vec2 uv) const;
};

}  // namespace igi
