#pragma once

// For tests only: the quantizers as first written, one value at a time, in double and with
// libm calls, straight from their definitions (docs/PROTOCOL.md). The library's table-driven
// versions must give the same codes and the same floats, bit for bit.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "Quantize.h"

namespace igi::proto::reference {

namespace detail {

constexpr int kMantissaBits = 9;
constexpr int kMaxMantissa = (1 << kMantissaBits) - 1;
constexpr int kMaxExponent = 31;
constexpr int kExponentBias = 30;
constexpr double kOctMax = (1 << kNormalBits) - 1;

inline double clean(float c) {
    return (c > 0.0f) ? static_cast<double>(c) : 0.0;
}

inline double signNotZero(double a) {
    return a >= 0.0 ? 1.0 : -1.0;
}

inline void fold(double& x, double& y) {
    const double fx = (1.0 - std::abs(y)) * signNotZero(x);
    const double fy = (1.0 - std::abs(x)) * signNotZero(y);
    x = fx;
    y = fy;
}

inline glm::dvec3 octDirection(int u, int v) {
    double x = u / kOctMax * 2.0 - 1.0;
    double y = v / kOctMax * 2.0 - 1.0;
    const double z = 1.0 - std::abs(x) - std::abs(y);
    if (z < 0.0) fold(x, y);
    const double len = std::sqrt(x * x + y * y + z * z);
    return {x / len, y / len, z / len};
}

}  // namespace detail

inline std::uint32_t encodeSharedExponent(glm::vec3 v, float scale) {
    using namespace detail;
    if (!(scale > 0.0f) || !std::isfinite(scale)) return 0;
    const double c[3] = {clean(v.x) / scale, clean(v.y) / scale, clean(v.z) / scale};
    const double maxc = std::min(std::max({c[0], c[1], c[2]}), 1.0);
    if (maxc < std::ldexp(0.5, -kExponentBias - kMantissaBits)) return 0;
    int e2 = 0;
    std::frexp(maxc, &e2);
    int exponent = std::clamp(e2 + kExponentBias, 0, kMaxExponent);
    double step = std::ldexp(1.0, exponent - kExponentBias - kMantissaBits);
    if (std::floor(maxc / step + 0.5) > kMaxMantissa && exponent < kMaxExponent) {
        ++exponent;
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

inline glm::vec3 decodeSharedExponent(std::uint32_t bits, float scale) {
    using namespace detail;
    const int exponent = static_cast<int>(bits >> 27);
    const double step = std::ldexp(1.0, exponent - kExponentBias - kMantissaBits) * scale;
    glm::vec3 out;
    for (int i = 0; i < 3; ++i)
        out[i] = static_cast<float>(((bits >> (kMantissaBits * i)) & kMaxMantissa) * step);
    return out;
}

inline std::uint8_t encodeSrgb8(float linear) {
    const double l = std::clamp(detail::clean(linear), 0.0, 1.0);
    const double s = l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055;
    return static_cast<std::uint8_t>(std::clamp(std::floor(s * 255.0 + 0.5), 0.0, 255.0));
}

inline float decodeSrgb8(std::uint8_t code) {
    const double s = code / 255.0;
    return static_cast<float>(s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4));
}

inline OctCode encodeOctNormal(glm::vec3 n) {
    using namespace detail;
    const glm::dvec3 d(n);
    const double l1 = std::abs(d.x) + std::abs(d.y) + std::abs(d.z);
    if (!(l1 > 1e-20) || !std::isfinite(l1)) return {};
    const glm::dvec3 unit = d / std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    double x = d.x / l1, y = d.y / l1;
    if (d.z < 0.0) fold(x, y);
    const double fu = (x * 0.5 + 0.5) * kOctMax, fv = (y * 0.5 + 0.5) * kOctMax;
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
    if (best == OctCode{}) best = {std::uint8_t(kOctMax), std::uint8_t(kOctMax)};
    return best;
}

inline glm::vec3 decodeOctNormal(OctCode code) {
    if (code == OctCode{}) return glm::vec3(0.0f);
    return glm::vec3(detail::octDirection(code.u, code.v));
}

inline std::uint16_t encodeLogDepth(float d, float d0) {
    if (std::isnan(d) || d == INFINITY) return kDepthInfinite;
    if (!(d > d0)) return 0;
    const double code = std::floor(std::log2(double(d) / double(d0)) * kDepthStepsPerOctave + 0.5);
    return static_cast<std::uint16_t>(std::min(code, double(kDepthInfinite - 1)));
}

inline float decodeLogDepth(std::uint16_t code, float d0) {
    if (code == kDepthInfinite) return INFINITY;
    return static_cast<float>(double(d0) * std::exp2(code / kDepthStepsPerOctave));
}

}  // namespace igi::proto::reference
