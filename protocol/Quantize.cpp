#include "Quantize.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cfloat>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <glm/geometric.hpp>

namespace igi::proto {
namespace {

constexpr int kMantissaBits = 9;
constexpr int kMaxMantissa = (1 << kMantissaBits) - 1;
constexpr int kMaxExponent = 31;
// Value = mantissa * 2^(exponent - kExponentBias - kMantissaBits). A bias of 30 makes the top
// exponent cover (0.5, 1], the range of a component divided by the plane's maximum.
constexpr int kExponentBias = 30;
// Half of the smallest step: anything below rounds to zero.
constexpr double kSmallestHalfStep = 0x1p-40;
static_assert(kSmallestHalfStep == 0.5 / (1ull << (kExponentBias + kMantissaBits)));
static_assert(kSharedExponentStepShift == kExponentBias + kMantissaBits);

constexpr int kOctCodes = 1 << (2 * kNormalBits);
constexpr int kDepthCodes = 1 << 16;

/// NaN, < 0 -> 0. Chosen on the bits, as floats >= +0 that are not NaN are exactly the bit
/// patterns up to that of +inf: integer operations, which loops vectorize (a float comparison
/// may trap on NaN, so the compiler keeps it a branch).
double clean(float c) {
    const std::uint32_t bits = std::bit_cast<std::uint32_t>(c);
    const std::uint32_t keep = bits <= 0x7F800000u ? ~0u : 0u;
    return static_cast<double>(std::bit_cast<float>(bits & keep));
}

/// 2^e for e in the range of normal doubles, exactly (what ldexp(1.0, e) gives, without a call).
double pow2(int e) {
    return std::bit_cast<double>(static_cast<std::uint64_t>(e + 1023) << 52);
}

/// floor(x + 0.5) for 0 <= x < 2^31: the same double addition, then truncation, which is floor
/// for non-negative values (std::floor is a library call without SSE4.1).
int roundHalfUp(double x) {
    return static_cast<int>(x + 0.5);
}

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

// ---- Tables, each built once per process on first use (thread-safe statics). The loops
// ---- fetch them once per plane, outside the loop.

/// octDirection of every code u | v << 8 in double, as the encoder compares candidates (1.5 MB,
/// built on the clients only).
const std::vector<glm::dvec3>& octEncodeTable() {
    static const std::vector<glm::dvec3> table = [] {
        std::vector<glm::dvec3> t(kOctCodes);
        for (int c = 0; c < kOctCodes; ++c) t[c] = octDirection(c & 0xFF, c >> 8);
        return t;
    }();
    return table;
}

/// The decoded normal of every code u | v << 8; code 0 is the zero vector (768 KB).
const std::vector<glm::vec3>& octDecodeTable() {
    static const std::vector<glm::vec3> table = [] {
        std::vector<glm::vec3> t(kOctCodes);
        for (int c = 1; c < kOctCodes; ++c) t[c] = glm::vec3(octDirection(c & 0xFF, c >> 8));
        return t;
    }();
    return table;
}

/// exp2(code / 2048) of every depth code, in double as the decoder multiplies (512 KB).
const std::vector<double>& depthDecodeTable() {
    static const std::vector<double> table = [] {
        std::vector<double> t(kDepthCodes);
        for (int c = 0; c < kDepthCodes; ++c) t[c] = std::exp2(c / kDepthStepsPerOctave);
        return t;
    }();
    return table;
}

const std::array<float, 256>& srgbDecodeTable() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) {
            const double s = i / 255.0;
            t[i] =
                static_cast<float>(s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4));
        }
        return t;
    }();
    return table;
}

/// The definition of the sRGB code of a linear value in [0, 1] (one pow per call).
int srgbCodeByDefinition(double l) {
    const double s = l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055;
    return static_cast<int>(std::clamp(std::floor(s * 255.0 + 0.5), 0.0, 255.0));
}

/// The sRGB encoder as a table: the code is a non-decreasing function of the float, so it is
/// fixed by the 255 thresholds where it steps up. The floats from 2^-13 to 1 are cut into 256
/// buckets per octave (by their bits), few enough for a small table and narrow enough that no
/// bucket holds two thresholds: a bucket's code is the code at its start, plus one past the
/// threshold it may hold. Below 2^-13 every code is 0 (the first threshold is 1.5e-4).
class SrgbEncodeTable {
  public:
    SrgbEncodeTable() {
        std::array<float, 257> threshold{};  // threshold[c]: the smallest float with code >= c
        for (int c = 1; c <= 255; ++c) threshold[c] = firstFloatWithCode(c);
        threshold[256] = INFINITY;
        if (!(threshold[1] > kLowest))
            throw std::logic_error("sRGB encode table: code 1 starts below 2^-13");
        for (std::uint32_t b = 0; b < kBuckets; ++b) {
            const std::uint32_t first = kLowestBits + (b << kBucketShift);
            const int code = srgbCodeByDefinition(std::bit_cast<float>(first));
            base_[b] = static_cast<std::uint8_t>(code);
            next_[b] = threshold[code + 1];
            const std::uint32_t last = first + (1u << kBucketShift) - 1;
            if (code <= 253 && std::bit_cast<std::uint32_t>(threshold[code + 2]) <= last)
                throw std::logic_error("sRGB encode table: two thresholds in one bucket");
        }
    }

    std::uint32_t code(float linear) const {
        const float l = linear > 0.0f ? std::min(linear, 1.0f) : 0.0f;  // NaN, < 0 -> 0
        if (l < kLowest) return 0;
        const std::uint32_t b = (std::bit_cast<std::uint32_t>(l) - kLowestBits) >> kBucketShift;
        return base_[b] + (l >= next_[b] ? 1u : 0u);
    }

  private:
    static constexpr float kLowest = 0x1p-13f;
    static constexpr std::uint32_t kLowestBits = std::bit_cast<std::uint32_t>(kLowest);
    static constexpr int kBucketShift = 23 - 8;  // 8 mantissa bits: 256 buckets per octave
    static constexpr std::uint32_t kBuckets =
        ((std::bit_cast<std::uint32_t>(1.0f) - kLowestBits) >> kBucketShift) + 1;

    /// Bisection over the bit patterns of [0, 1], which order like the floats.
    static float firstFloatWithCode(int c) {
        std::uint32_t below = 0, at = std::bit_cast<std::uint32_t>(1.0f);
        while (at - below > 1) {
            const std::uint32_t mid = below + (at - below) / 2;
            (srgbCodeByDefinition(std::bit_cast<float>(mid)) >= c ? at : below) = mid;
        }
        return std::bit_cast<float>(at);
    }

    std::array<std::uint8_t, kBuckets> base_{};
    std::array<float, kBuckets> next_{};
};

const SrgbEncodeTable& srgbEncodeTable() {
    static const SrgbEncodeTable table;
    return table;
}

// ---- One value, the arithmetic of the definitions without their library calls.

/// The code of a pixel from its components already cleaned and divided by the scale.
std::uint32_t sharedExponentCode(const double* c) {
    const double maxc = std::min(std::max({c[0], c[1], c[2]}), 1.0);
    if (maxc < kSmallestHalfStep) return 0;
    // frexp: maxc = f * 2^e2 with f in [0.5, 1), read from the bits of this normal double.
    const int e2 = static_cast<int>(std::bit_cast<std::uint64_t>(maxc) >> 52) - 1022;
    int exponent = std::clamp(e2 + kExponentBias, 0, kMaxExponent);
    // Dividing by the step, a power of two, is exactly multiplying by its inverse.
    double inverseStep = pow2(kExponentBias + kMantissaBits - exponent);
    if (roundHalfUp(maxc * inverseStep) > kMaxMantissa && exponent < kMaxExponent) {
        ++exponent;  // rounding carried into a tenth bit
        inverseStep *= 0.5;
    }
    std::uint32_t bits = static_cast<std::uint32_t>(exponent) << 27;
    for (int i = 0; i < 3; ++i) {
        const int m = std::min(roundHalfUp(std::min(c[i], 1.0) * inverseStep), kMaxMantissa);
        bits |= static_cast<std::uint32_t>(m) << (kMantissaBits * i);
    }
    return bits;
}

std::uint32_t octCode(glm::vec3 n, const glm::dvec3* directions) {
    const glm::dvec3 d(n);
    const double l1 = std::abs(d.x) + std::abs(d.y) + std::abs(d.z);
    if (!(l1 > 1e-20) || !std::isfinite(l1)) return 0;  // zero (or broken): "no normal"
    const glm::dvec3 unit = d / std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    double x = d.x / l1, y = d.y / l1;
    if (d.z < 0.0) fold(x, y);
    // |x|, |y| <= 1, so fu, fv are in [0, 255] and truncation is floor.
    const int u0 = static_cast<int>((x * 0.5 + 0.5) * kOctMax);
    const int v0 = static_cast<int>((y * 0.5 + 0.5) * kOctMax);
    // Of the four surrounding codes, take the one nearest in angle, not in the plane: this
    // brings the worst case for 8 bits from 0.95 to 0.63 degrees.
    std::uint32_t best = 0;
    double bestCos = -2.0;
    for (int i = 0; i < 4; ++i) {
        const int u = std::min(u0 + (i & 1), int(kOctMax));
        const int v = std::min(v0 + (i >> 1), int(kOctMax));
        const std::uint32_t code = static_cast<std::uint32_t>(u | v << 8);
        const double c = glm::dot(directions[code], unit);
        if (c > bestCos) {
            bestCos = c;
            best = code;
        }
    }
    return best == 0 ? 0xFFFFu : best;  // (0, 0) and (max, max) both are -z
}

std::uint32_t logDepthCode(float d, float d0) {
    if (std::isnan(d) || d == INFINITY) return kDepthInfinite;
    if (!(d > d0)) return 0;
    // d / d0 >= 1, so the rounded value is >= 0.5 and truncation is floor.
    const double x = std::log2(double(d) / double(d0)) * kDepthStepsPerOctave + 0.5;
    return x < double(kDepthInfinite - 1) ? static_cast<std::uint32_t>(x) : kDepthInfinite - 1u;
}

/// Log depth codes of one plane without a division and a log2 call per pixel. The code is
/// floor(y + 0.5) for y = log2(d / d0) * 2048; an approximation of y within 1e-9 gives the same
/// code as the definition's double arithmetic (itself within 1e-9 of the exact y) unless y + 0.5
/// lies within about that distance of an integer. Those pixels, and any that are not ordinary (d
/// not above d0, not a normal float, beyond the clamp), take the definition's path.
class LogDepthEncoder {
  public:
    explicit LogDepthEncoder(float d0) : table_(table()), d0_(d0), log2d0_(std::log2(double(d0))) {}

    std::uint32_t code(float d) const {
        const std::uint32_t bits = std::bit_cast<std::uint32_t>(d);
        const std::uint32_t biased = bits >> 23;  // sign and exponent: 1 .. 254 is normal > 0
        if (d > d0_ && biased >= 1 && biased <= 254) {
            // y + 0.5 is near 0.5 or more (d > d0): truncation is floor.
            const double y = (log2Normal(bits) - log2d0_) * kDepthStepsPerOctave + 0.5;
            if (y < kFastBelow) {
                const std::uint32_t whole = static_cast<std::uint32_t>(y);
                const double fraction = y - whole;
                if (fraction > kMargin && fraction < 1.0 - kMargin) return whole;
            }
        }
        return logDepthCode(d, d0_);
    }

  private:
    static constexpr double kMargin = 1e-6;  // a thousand times the error of either path
    static constexpr double kFastBelow = 65000.0;
    static constexpr int kTableBits = 7;

    /// log2 of a positive normal float given by its bits, within about 1e-13: the exponent,
    /// then the mantissa m in [1, 2) as m * inv[j] = 1 + r with |r| < 2^-8 (j: m's top bits),
    /// log2(m) = log2(1 + r) - log2(inv[j]) with four terms of the series of log(1 + r).
    double log2Normal(std::uint32_t bits) const {
        const Table& t = table_;
        const int exponent = static_cast<int>(bits >> 23) - 127;
        const std::uint32_t j = (bits >> (23 - kTableBits)) & ((1u << kTableBits) - 1);
        const double m =
            std::bit_cast<double>(std::uint64_t{bits & 0x7FFFFF} << 29 | 0x3FF0000000000000ull);
        const double r = m * t.inverse[j] - 1.0;
        const double series = r * (1.0 + r * (-0.5 + r * (1.0 / 3.0 + r * -0.25)));
        return exponent + (series * (1.0 / std::numbers::ln2) - t.log2Inverse[j]);
    }

    struct Table {
        std::array<double, 1 << kTableBits> inverse, log2Inverse;
    };
    static const Table& table() {
        static const Table t = [] {
            Table table;
            for (int j = 0; j < (1 << kTableBits); ++j) {
                table.inverse[j] = 1.0 / (1.0 + (j + 0.5) / (1 << kTableBits));
                table.log2Inverse[j] = std::log2(table.inverse[j]);
            }
            return table;
        }();
        return t;
    }

    const Table& table_;
    float d0_;
    double log2d0_;
};

float logDepthValue(std::uint32_t code, double d0, const double* exp2Table) {
    return code == kDepthInfinite ? INFINITY : static_cast<float>(d0 * exp2Table[code]);
}

/// Flat surfaces repeat their albedo and normal from pixel to pixel: a pixel bit for bit equal
/// to the one before gets that one's code without computing it.
class RepeatCache {
  public:
    /// When `v` equals the previous pixel's value, copies its code to out[i].
    bool hit(glm::vec3 v, std::span<std::uint32_t> out, std::size_t i) {
        const Bits bits = {std::bit_cast<std::uint32_t>(v.x), std::bit_cast<std::uint32_t>(v.y),
                           std::bit_cast<std::uint32_t>(v.z)};
        const bool same = i > 0 && bits == previous_;
        if (same) out[i] = out[i - 1];
        previous_ = bits;
        return same;
    }

  private:
    using Bits = std::array<std::uint32_t, 3>;
    Bits previous_{};
};

static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "planes are read as arrays of floats");

template <typename Step>
void decodeSharedExponentsIn(std::span<const std::uint32_t> in, float scale,
                             std::span<glm::vec3> out) {
    Step step[kMaxExponent + 1];
    for (int e = 0; e <= kMaxExponent; ++e)
        step[e] = static_cast<Step>(pow2(e - kExponentBias - kMantissaBits) * scale);
    for (std::size_t i = 0; i < in.size(); ++i) {
        const std::uint32_t w = in[i];
        const Step s = step[w >> 27];
        out[i] = glm::vec3(static_cast<float>(static_cast<Step>(w & kMaxMantissa) * s),
                           static_cast<float>(static_cast<Step>((w >> 9) & kMaxMantissa) * s),
                           static_cast<float>(static_cast<Step>((w >> 18) & kMaxMantissa) * s));
    }
}

}  // namespace

// The single values go through the plane functions, so that the per-pixel code has one caller
// and is inlined into the plane loops.

const double* logDepthOctaveFactors() {
    static const double* octave = [] {
        const double* full = depthDecodeTable().data();
        constexpr int kPerOctave = static_cast<int>(kDepthStepsPerOctave);
        for (int c = 0; c < kDepthCodes; ++c)
            if (full[c] != full[c % kPerOctave] * pow2(c / kPerOctave))
                return (const double*)nullptr;
        return full;  // its first octave
    }();
    return octave;
}

const float* srgbDecodeValues() {
    return srgbDecodeTable().data();
}

const glm::vec3* octNormalValues() {
    return octDecodeTable().data();
}

const double* logDepthFactors() {
    return depthDecodeTable().data();
}

std::uint32_t encodeSharedExponent(glm::vec3 v, float scale) {
    std::uint32_t code = 0;
    encodeSharedExponents({&v, 1}, scale, {&code, 1});
    return code;
}

glm::vec3 decodeSharedExponent(std::uint32_t bits, float scale) {
    const int exponent = static_cast<int>(bits >> 27);
    const double step = pow2(exponent - kExponentBias - kMantissaBits) * scale;
    glm::vec3 out;
    for (int i = 0; i < 3; ++i)
        out[i] = static_cast<float>(((bits >> (kMantissaBits * i)) & kMaxMantissa) * step);
    return out;
}

std::uint8_t encodeSrgb8(float linear) {
    return static_cast<std::uint8_t>(srgbEncodeTable().code(linear));
}

float decodeSrgb8(std::uint8_t code) {
    return srgbDecodeTable()[code];
}

OctCode encodeOctNormal(glm::vec3 n) {
    std::uint32_t c = 0;
    encodeOctNormals({&n, 1}, {&c, 1});
    return {static_cast<std::uint8_t>(c & 0xFF), static_cast<std::uint8_t>(c >> 8)};
}

glm::vec3 decodeOctNormal(OctCode code) {
    return octDecodeTable()[code.u | code.v << 8];
}

std::uint16_t encodeLogDepth(float d, float d0) {
    return static_cast<std::uint16_t>(logDepthCode(d, d0));
}

float decodeLogDepth(std::uint16_t code, float d0) {
    return logDepthValue(code, d0, depthDecodeTable().data());
}

void encodeSharedExponents(std::span<const glm::vec3> in, float scale,
                           std::span<std::uint32_t> out) {
    assert(in.size() == out.size());
    if (!(scale > 0.0f) || !std::isfinite(scale)) {
        std::fill(out.begin(), out.end(), 0u);
        return;
    }
    // In chunks, first the divisions alone over the components as a flat array, which the
    // compiler turns into packed divisions (the same IEEE quotients), then the codes.
    constexpr std::size_t kChunk = 256;
    double c[3 * kChunk];
    const double divisor = scale;
    for (std::size_t first = 0; first < in.size(); first += kChunk) {
        const std::size_t n = std::min(kChunk, in.size() - first);
        const float* f = &in[first].x;
        for (std::size_t k = 0; k < 3 * n; ++k) c[k] = clean(f[k]) / divisor;
        for (std::size_t i = 0; i < n; ++i) {
            const double* p = c + 3 * i;
            // No positive component (most of the unfiltered plane): code 0 at once.
            out[first + i] = (p[0] > 0.0 || p[1] > 0.0 || p[2] > 0.0) ? sharedExponentCode(p) : 0u;
        }
    }
}

void decodeSharedExponents(std::span<const std::uint32_t> in, float scale,
                           std::span<glm::vec3> out) {
    assert(in.size() == out.size());
    // The definition multiplies in double, where mantissa (9 bits) times step (scale's 24 bits
    // times a power of two) is exact, and rounds once to float. A float multiply rounds that
    // same exact product once, provided every step is itself a float: scale * 2^-39 normal.
    if (scale >= 0x1p-87f && scale <= FLT_MAX)
        decodeSharedExponentsIn<float>(in, scale, out);
    else
        decodeSharedExponentsIn<double>(in, scale, out);
}

void encodeSrgb8Triples(std::span<const glm::vec3> in, std::span<std::uint32_t> out) {
    assert(in.size() == out.size());
    const SrgbEncodeTable& table = srgbEncodeTable();
    RepeatCache repeat;
    for (std::size_t i = 0; i < in.size(); ++i) {
        if (repeat.hit(in[i], out, i)) continue;
        out[i] = table.code(in[i].x) | table.code(in[i].y) << 8 | table.code(in[i].z) << 16;
    }
}

void decodeSrgb8Triples(std::span<const std::uint32_t> in, std::span<glm::vec3> out) {
    assert(in.size() == out.size());
    const float* table = srgbDecodeTable().data();
    for (std::size_t i = 0; i < in.size(); ++i) {
        const std::uint32_t w = in[i];
        out[i] = glm::vec3(table[w & 0xFF], table[(w >> 8) & 0xFF], table[(w >> 16) & 0xFF]);
    }
}

void encodeOctNormals(std::span<const glm::vec3> in, std::span<std::uint32_t> out) {
    assert(in.size() == out.size());
    const glm::dvec3* directions = octEncodeTable().data();
    RepeatCache repeat;
    for (std::size_t i = 0; i < in.size(); ++i)
        if (!repeat.hit(in[i], out, i)) out[i] = octCode(in[i], directions);
}

void decodeOctNormals(std::span<const std::uint32_t> in, std::span<glm::vec3> out) {
    assert(in.size() == out.size());
    const glm::vec3* table = octDecodeTable().data();
    for (std::size_t i = 0; i < in.size(); ++i) out[i] = table[in[i] & 0xFFFF];
}

void encodeLogDepths(std::span<const float> in, float d0, std::span<std::uint32_t> out) {
    assert(in.size() == out.size());
    const LogDepthEncoder encoder(d0);
    for (std::size_t i = 0; i < in.size(); ++i) out[i] = encoder.code(in[i]);
}

void decodeLogDepths(std::span<const std::uint32_t> in, float d0, std::span<float> out) {
    assert(in.size() == out.size());
    const double* table = depthDecodeTable().data();
    for (std::size_t i = 0; i < in.size(); ++i) out[i] = logDepthValue(in[i] & 0xFFFF, d0, table);
}

}  // namespace igi::proto
