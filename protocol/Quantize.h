#pragma once

#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

namespace igi::proto {

// Per-pixel quantizers of the tile channels (see docs/PROTOCOL.md for the bounds). Each is a
// pure function of its inputs, so encoder and decoder agree bit for bit on every machine.

/// Shared-exponent RGB (RGB9E5-style: three 9-bit mantissas, one 5-bit exponent) of `v / scale`,
/// where `scale` > 0 is the largest component of the whole plane, so only relative magnitudes
/// within a tile are quantized: the pixel's largest component keeps a relative error below
/// 2^-9 and components down to 2^-39 * scale stay non-zero. Negative and NaN components are 0.
std::uint32_t encodeSharedExponent(glm::vec3 v, float scale);
glm::vec3 decodeSharedExponent(std::uint32_t bits, float scale);

/// Linear [0, 1] to an 8-bit sRGB code (clamped; NaN is 0) and back.
std::uint8_t encodeSrgb8(float linear);
float decodeSrgb8(std::uint8_t code);

/// Octahedral unit vector with `kNormalBits` per coordinate, rounded to the code nearest in
/// angle. Code (0, 0) is reserved for the zero vector ("no normal"); the only direction it would
/// otherwise name, -z, is also named by (max, max), which is used instead.
struct OctCode {
    std::uint8_t u = 0, v = 0;
    bool operator==(const OctCode&) const = default;
};
constexpr int kNormalBits = 8;
OctCode encodeOctNormal(glm::vec3 n);
glm::vec3 decodeOctNormal(OctCode code);

/// Depth as a logarithm relative to the tile's smallest finite depth `d0` > 0:
/// round(log2(d / d0) * 2048), clamped to [0, 0xFFFE]; 0xFFFF is +inf (no hit), also used for
/// NaN. The relative error is below 2^(1/4096) - 1 = 1.7e-4 for d in [d0, d0 * 2^31.99].
constexpr std::uint16_t kDepthInfinite = 0xFFFF;
constexpr double kDepthStepsPerOctave = 2048.0;
std::uint16_t encodeLogDepth(float d, float d0);
float decodeLogDepth(std::uint16_t code, float d0);

/// What the plane decoders below look values up in, for code that dequantizes planes its own
/// way (CodedFrame): each built once per process, entry for entry the per-value decoders'
/// results. The linear value of every sRGB code (256); the normal of every octahedral code
/// u | v << 8 (65536, code 0 the zero vector); exp2(code / 2048) of every log depth code
/// (65536: the depth is float(d0 * factor), +inf for kDepthInfinite).
const float* srgbDecodeValues();
const glm::vec3* octNormalValues();
const double* logDepthFactors();
/// The first 2048 log depth factors, exp2(f / 2048), when every factor is exactly
/// factor[c % 2048] * 2^(c / 2048) (checked once against the full table: exp2 of this
/// process's libm scales so); null when not. A 16 KB table that stays in the cache.
const double* logDepthOctaveFactors();
/// A shared-exponent code's component is mantissa * scale * 2^(exponent - this).
constexpr int kSharedExponentStepShift = 39;

// Whole planes at once, for the tile codec: bit for bit the codes and values of the per-value
// functions above, many times faster (tables built once per process, no libm calls and no
// per-pixel set-up in the loops). Codes are held in u32 words packed as on the wire before the
// byte shuffle: shared exponent as above; sRGB triples red | green << 8 | blue << 16; octahedral
// normals u | v << 8; log depth the u16 code. `in` and `out` must have the same size.
void encodeSharedExponents(std::span<const glm::vec3> in, float scale,
                           std::span<std::uint32_t> out);
void decodeSharedExponents(std::span<const std::uint32_t> in, float scale,
                           std::span<glm::vec3> out);
void encodeSrgb8Triples(std::span<const glm::vec3> in, std::span<std::uint32_t> out);
void decodeSrgb8Triples(std::span<const std::uint32_t> in, std::span<glm::vec3> out);
void encodeOctNormals(std::span<const glm::vec3> in, std::span<std::uint32_t> out);
void decodeOctNormals(std::span<const std::uint32_t> in, std::span<glm::vec3> out);
void encodeLogDepths(std::span<const float> in, float d0, std::span<std::uint32_t> out);
void decodeLogDepths(std::span<const std::uint32_t> in, float d0, std::span<float> out);

}  // namespace igi::proto
