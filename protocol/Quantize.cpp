#include "Quantize.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>

namespace igi::proto {
namespace {

constexpr int kMantissaBits = 9;
constexpr int kMaxMantissa = (1 << kMantissaBits) - 1;
constexpr int kMaxExponent = 31;
// Value = mantissa * 2^(exponent - kExponentBias - kMantissaBits). A bias of 30 makes the top
// exponent cover (0.5, 1], the range of a component divided by the plane's maximum.
constexpr int kExponentBias = 30;

double clean(float c) {
    return (c > 0.0f) ? static_cast<double>(c) : 0.0;
}  // NaN, < 0 -> 0

double signNotZero(double a) {
    return a >= 0.0 ? 1.0 : -1.0;
}

/// Folds the octahedron's lower half over the upper one (and back: it is an involution).
void fold(double& x, double& y) {
    const double fx = (1.0 - std::abs(y)) * signNotZero(x);
    const double fy = (1.0 - std::abs(x)) * signNotZero(y);
    x = fx;
    y = fy;
}

constexpr double kOctMax = (1 << kNormalBits) - 1;

glm::dvec3 octDirection(int u, int v) {
    double x = u / kOctMax * 2.0 - 1.0;
    double y = v / kOctMax * 2.0 - 1.0;
    const double z = 1.0 - std::abs(x) - std::abs(y);
    if (z < 0.0) fold(x, y);
    const double len = std::sqrt(x * x + y * y + z * z);
    return {x / len, y / len, z / len};
}

}  // namespace

std::uint32_t encodeSharedExponent(glm::vec3 v, float scale) {
    if (!(scale > 0.0f) || !std::isfinite(scale)) return 0;
    const double c[3] = {clean(v.x) / scale, clean(v.y) / scale, clean(v.z) / scale};
    const double maxc = std::min(std::max({c[0], c[1], c[2]}), 1.0);
    // Smaller than half of the smallest step: rounds to zero.
    if (maxc < std::ldexp(0.5, -kExponentBias - kMantissaBits)) return 0;
    int e2 = 0;
    std::frexp(maxc, &e2);  // maxc = f * 2^e2, f in [0.5, 1): floor(log2(maxc)) = e2 - 1
    int exponent = std::clamp(e2 + kExponentBias, 0, kMaxExponent);
    double step = std::ldexp(1.0, exponent - kExponentBias - kMantissaBits);
    if (std::floor(maxc / step + 0.5) > kMaxMantissa && exponent < kMaxExponent) {
        ++exponent;  // rounding carried into a tenth bit
        step *= 2.0;
    }
    std::uint32_t bits = static_cast<std::uint32_t>(exponent) << 27;
    for (int i = 0; i < 3; ++i) {
        const double m = std::min(std::floor(std::min(c[i], 1.0) / step + 0.5),
                                  static_cast<double>(kMaxMantissa));
        bits |= static_cast<std::uint32_t>(m) << (kMantissaBits * i);
    }
    return bits;
}

glm::vec3 decodeSharedExponent(std::uint32_t bits, float scale) {
    const int exponent = static_cast<int>(bits >> 27);
    const double step = std::ldexp(1.0, exponent - kExponentBias - kMantissaBits) * scale;
    glm::vec3 out;
    for (int i = 0; i < 3; ++i)
        out[i] = static_cast<float>(((bits >> (kMantissaBits * i)) & kMaxMantissa) * step);
    return out;
}

std::uint8_t encodeSrgb8(float linear) {
    const double l = std::clamp(clean(linear), 0.0, 1.0);
    const double s = l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055;
    return static_cast<std::uint8_t>(std::clamp(std::floor(s * 255.0 + 0.5), 0.0, 255.0));
}

float decodeSrgb8(std::uint8_t code) {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) {
            const double s = i / 255.0;
            t[i] =
                static_cast<float>(s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4));
        }
        return t;
    }();
    return table[code];
}

OctCode encodeOctNormal(glm::vec3 n) {
    const glm::dvec3 d(n);
    const double l1 = std::abs(d.x) + std::abs(d.y) + std::abs(d.z);
    if (!(l1 > 1e-20) || !std::isfinite(l1)) return {};  // zero (or broken): "no normal"
    const glm::dvec3 unit = d / std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    double x = d.x / l1, y = d.y / l1;
    if (d.z < 0.0) fold(x, y);
    const double fu = (x * 0.5 + 0.5) * kOctMax, fv = (y * 0.5 + 0.5) * kOctMax;
    // Of the four surrounding codes, take the one nearest in angle, not in the plane: this
    // brings the worst case for 8 bits from 0.95 to 0.63 degrees.
    OctCode best;
    double bestCos = -2.0;
    for (int i = 0; i < 4; ++i) {
        const int u = std::clamp(static_cast<int>(std::floor(fu)) + (i & 1), 0, int(kOctMax));
        const int v = std::clamp(static_cast<int>(std::floor(fv)) + (i >> 1), 0, int(kOctMax));
        const double c = glm::dot(octDirection(u, v), unit);
        if (c > bestCos) {
            bestCos = c;
            best = {static_cast<std::uint8_t>(u), static_cast<std::uint8_t>(v)};
        }
    }
    if (best == OctCode{}) best = {std::uint8_t(kOctMax), std::uint8_t(kOctMax)};  // both are -z
    return best;
}

glm::vec3 decodeOctNormal(OctCode code) {
    if (code == OctCode{}) return glm::vec3(0.0f);
    return glm::vec3(octDirection(code.u, code.v));
}

std::uint16_t encodeLogDepth(float d, float d0) {
    if (std::isnan(d) || d == INFINITY) return kDepthInfinite;
    if (!(d > d0)) return 0;
    const double code = std::floor(std::log2(double(d) / double(d0)) * kDepthStepsPerOctave + 0.5);
    return static_cast<std::uint16_t>(std::min(code, double(kDepthInfinite - 1)));
}

float decodeLogDepth(std::uint16_t code, float d0) {
    if (code == kDepthInfinite) return INFINITY;
    return static_cast<float>(double(d0) * std::exp2(code / kDepthStepsPerOctave));
}

}  // namespace igi::proto
