#include "Quantize.h"

#include <gtest/gtest.h>

#include <bit>
#include <cfloat>
#include <cmath>
#include <iostream>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "QuantizeReference.h"

namespace igi::proto {
namespace {

TEST(Quantize, SharedExponentKeepsThePlaneMaximumExactly) {
    for (float scale : {1e-12f, 3.7e-5f, 1.0f, 123.0f, 1e12f}) {
        const glm::vec3 v(scale, 0.5f * scale, 0.0f);
        const glm::vec3 d = decodeSharedExponent(encodeSharedExponent(v, scale), scale);
        EXPECT_EQ(d.x, scale);
        EXPECT_EQ(d.y, 0.5f * scale);
        EXPECT_EQ(d.z, 0.0f);
    }
}

TEST(Quantize, SharedExponentRelativeErrorOfTheLargestComponent) {
    // Within a plane, any pixel whose largest component is at least 2^-30 of the plane's
    // maximum keeps that component within 2^-9 (relative), at any absolute magnitude.
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> logRel(-30.0 * std::log10(2.0), 0.0), u(0.0, 1.0);
    double worst = 0.0;
    for (float scale : {1e-12f, 1.0f, 1e12f}) {
        for (int i = 0; i < 200000; ++i) {
            const float m = static_cast<float>(scale * std::pow(10.0, logRel(rng)));
            const glm::vec3 v(m, static_cast<float>(m * u(rng)), static_cast<float>(m * u(rng)));
            const glm::vec3 d = decodeSharedExponent(encodeSharedExponent(v, scale), scale);
            worst = std::max(worst, std::abs(double(d.x) - m) / m);
        }
    }
    std::cout << "shared exponent: worst relative error of a pixel's largest component " << worst
              << "\n";
    EXPECT_LE(worst, std::ldexp(1.0, -9) * 1.0001);
}

TEST(Quantize, SharedExponentRangeAndInvalidValues) {
    const float scale = 1.0f;
    EXPECT_GT(decodeSharedExponent(encodeSharedExponent(glm::vec3(1e-11f), scale), scale).x, 0.0f);
    EXPECT_EQ(encodeSharedExponent(glm::vec3(1e-13f), scale), 0u);  // below 2^-40: zero
    EXPECT_EQ(encodeSharedExponent(glm::vec3(-1.0f), scale), 0u);
    EXPECT_EQ(encodeSharedExponent(glm::vec3(NAN), scale), 0u);
    EXPECT_EQ(decodeSharedExponent(encodeSharedExponent(glm::vec3(INFINITY), scale), scale).x,
              scale);
}

TEST(Quantize, SrgbCodesRoundTripAndErrorIsHalfAStep) {
    for (int c = 0; c < 256; ++c)
        EXPECT_EQ(encodeSrgb8(decodeSrgb8(static_cast<std::uint8_t>(c))), c);
    EXPECT_EQ(decodeSrgb8(0), 0.0f);
    EXPECT_EQ(decodeSrgb8(255), 1.0f);
    EXPECT_EQ(encodeSrgb8(2.0f), 255);
    EXPECT_EQ(encodeSrgb8(-1.0f), 0);
    EXPECT_EQ(encodeSrgb8(NAN), 0);
    for (int i = 0; i <= 10000; ++i) {
        const float l = i / 10000.0f;
        const int c = encodeSrgb8(l);
        // The neighbouring codes must not be closer in sRGB space than the chosen one.
        const float lo = decodeSrgb8(static_cast<std::uint8_t>(std::max(c - 1, 0)));
        const float hi = decodeSrgb8(static_cast<std::uint8_t>(std::min(c + 1, 255)));
        EXPECT_LE(lo, l);
        EXPECT_GE(hi, l);
    }
}

TEST(Quantize, OctahedralNormalMaxAngularErrorIsBelowOneDegree) {
    std::mt19937 rng(5);
    std::normal_distribution<float> g;
    double worst = 0.0;
    auto check = [&](glm::vec3 n) {
        n = glm::normalize(n);
        const glm::vec3 d = decodeOctNormal(encodeOctNormal(n));
        const double c = std::clamp(double(glm::dot(glm::dvec3(d), glm::dvec3(n))), -1.0, 1.0);
        worst = std::max(worst, std::acos(c) * 180.0 / M_PI);
        EXPECT_NEAR(glm::length(d), 1.0f, 1e-5f);
    };
    for (int i = 0; i < 1000000; ++i) check({g(rng), g(rng), g(rng)});
    for (glm::vec3 axis :
         {glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, -1, 0),
          glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::vec3(1, 1, 0), glm::vec3(1, -1, -1e-7f)})
        check(axis);
    std::cout << "octahedral normals, 2 x u8: max angular error " << worst << " degrees\n";
    EXPECT_LT(worst, 1.0);
}

TEST(Quantize, ZeroNormalIsReservedAndMinusZStillWorks) {
    EXPECT_EQ(encodeOctNormal(glm::vec3(0.0f)), OctCode{});
    EXPECT_EQ(decodeOctNormal(OctCode{}), glm::vec3(0.0f));
    EXPECT_EQ(encodeOctNormal(glm::vec3(NAN)), OctCode{});
    const glm::vec3 down = decodeOctNormal(encodeOctNormal(glm::vec3(0, 0, -1)));
    EXPECT_NE(encodeOctNormal(glm::vec3(0, 0, -1)), OctCode{});
    EXPECT_NEAR(down.z, -1.0f, 1e-6f);
    // Unnormalized input is normalized first.
    EXPECT_NEAR(decodeOctNormal(encodeOctNormal(glm::vec3(0, 5, 0))).y, 1.0f, 1e-4f);
}

TEST(Quantize, LogDepthRelativeErrorIsBelowOnePerMille) {
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> octaves(0.0, 31.9);
    double worst = 0.0;
    for (float d0 : {1e-6f, 0.37f, 5e5f}) {
        for (int i = 0; i < 100000; ++i) {
            const float d = static_cast<float>(d0 * std::exp2(octaves(rng)));
            const float q = decodeLogDepth(encodeLogDepth(d, d0), d0);
            worst = std::max(worst, std::abs(double(q) - d) / d);
        }
        EXPECT_EQ(decodeLogDepth(encodeLogDepth(d0, d0), d0), d0);
    }
    std::cout << "log depth: worst relative error " << worst << "\n";
    EXPECT_LT(worst, 1e-3);
    EXPECT_LT(worst, 1.8e-4);  // the documented bound, 2^(1/4096) - 1
}

TEST(Quantize, LogDepthSpecialValues) {
    EXPECT_EQ(encodeLogDepth(INFINITY, 1.0f), kDepthInfinite);
    EXPECT_EQ(encodeLogDepth(NAN, 1.0f), kDepthInfinite);
    EXPECT_EQ(decodeLogDepth(kDepthInfinite, 1.0f), INFINITY);
    EXPECT_EQ(encodeLogDepth(0.5f, 1.0f), 0);         // below the reference: clamped to it
    EXPECT_EQ(encodeLogDepth(1e30f, 1e-6f), 0xFFFE);  // beyond 2^32 d0: clamped, still finite
}

// ---- The table-driven quantizers against the reference (QuantizeReference.h), bit for bit ----

std::uint32_t bitsOf(float f) {
    return std::bit_cast<std::uint32_t>(f);
}

/// Equal as bit patterns, so that -0 against +0 or two different NaNs count as different.
::testing::AssertionResult sameBits(glm::vec3 a, glm::vec3 b) {
    for (int i = 0; i < 3; ++i)
        if (bitsOf(a[i]) != bitsOf(b[i]))
            return ::testing::AssertionFailure()
                   << "component " << i << ": " << a[i] << " (0x" << std::hex << bitsOf(a[i])
                   << ") against " << b[i] << " (0x" << bitsOf(b[i]) << ")";
    return ::testing::AssertionSuccess();
}

/// Scales that exercise both decoding paths (float steps from 2^-87 up, double below), the
/// ends of the float range and short mantissas (which make exact ties and powers of two).
const std::vector<float> kScales = {1.0f,     3.0f,   0.625f,   0.1f,
                                    3.7e-5f,  1e-12f, 1e12f,    FLT_MAX,
                                    FLT_MIN,  1e-40f, 0x1p-87f, std::nextafter(0x1p-87f, 0.0f),
                                    0x1p-100f};

/// Shared-exponent codes: every combination of the edge exponents and mantissas, then random.
std::vector<std::uint32_t> sharedExponentCodes(std::size_t randomCount, std::uint32_t seed) {
    std::vector<std::uint32_t> codes;
    const std::uint32_t mantissas[] = {0, 1, 2, 255, 256, 510, 511};
    for (std::uint32_t e : {0u, 1u, 15u, 29u, 30u, 31u})
        for (std::uint32_t r : mantissas)
            for (std::uint32_t g : mantissas)
                for (std::uint32_t b : mantissas) codes.push_back(e << 27 | b << 18 | g << 9 | r);
    std::mt19937 rng(seed);
    for (std::size_t i = 0; i < randomCount; ++i) codes.push_back(rng());
    return codes;
}

TEST(QuantizeFast, SharedExponentDecodingMatchesTheReference) {
    std::size_t checked = 0;
    for (float scale : kScales) {
        SCOPED_TRACE("scale " + std::to_string(scale));
        const auto codes = sharedExponentCodes(300000, bitsOf(scale));
        std::vector<glm::vec3> fast(codes.size());
        decodeSharedExponents(codes, scale, fast);
        for (std::size_t i = 0; i < codes.size(); ++i) {
            const glm::vec3 expected = reference::decodeSharedExponent(codes[i], scale);
            ASSERT_TRUE(sameBits(fast[i], expected)) << "code 0x" << std::hex << codes[i];
            ASSERT_TRUE(sameBits(decodeSharedExponent(codes[i], scale), expected));
        }
        checked += codes.size();
    }
    EXPECT_GT(checked, 3'000'000u);
}

/// Pixels for the shared-exponent encoder: magnitudes from far below the smallest step to above
/// the scale, exact ties and powers of two, and zero, negative, NaN, infinite and subnormal
/// components.
std::vector<glm::vec3> sharedExponentPixels(float scale, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> octaves(-45.0, 1.5), u(0.0, 1.0);
    std::uniform_int_distribution<int> mantissa(0, 1023), exponent(-40, 0), pick(0, 15);
    auto component = [&](double top) -> float {
        switch (pick(rng)) {
            case 0:
                return 0.0f;
            case 1:
                return -static_cast<float>(top * u(rng));
            case 2:
                return NAN;
            case 3:
                return INFINITY;
            case 4:
                return 1e-44f;  // subnormal
            case 5:             // a tie or a power of two in units of some step, when representable
                return static_cast<float>(scale * std::ldexp(mantissa(rng) + 0.5, exponent(rng)));
            case 6:
                return static_cast<float>(scale * std::ldexp(1.0, exponent(rng)));
            default:
                return static_cast<float>(top * u(rng));
        }
    };
    std::vector<glm::vec3> pixels;
    for (int i = 0; i < 100000; ++i) {
        const double top = scale * std::exp2(octaves(rng));
        pixels.emplace_back(component(top), component(top), component(top));
    }
    for (float c : {scale, std::nextafter(scale, 0.0f), 0.5f * scale, scale * 0x1p-40f,
                    scale * 0x1p-39f, scale * 0x1p-30f, scale * (1.0f - 0x1p-10f)})
        pixels.emplace_back(c, 0.5f * c, 0.25f * c);
    return pixels;
}

TEST(QuantizeFast, SharedExponentEncodingMatchesTheReference) {
    for (float scale : kScales) {
        SCOPED_TRACE("scale " + std::to_string(scale));
        const auto pixels = sharedExponentPixels(scale, bitsOf(scale));
        std::vector<std::uint32_t> fast(pixels.size());
        encodeSharedExponents(pixels, scale, fast);
        for (std::size_t i = 0; i < pixels.size(); ++i) {
            const std::uint32_t expected = reference::encodeSharedExponent(pixels[i], scale);
            ASSERT_EQ(fast[i], expected) << pixels[i].x << " " << pixels[i].y << " " << pixels[i].z;
            ASSERT_EQ(encodeSharedExponent(pixels[i], scale), expected);
        }
    }
    // Invalid scales give zeros, as the reference does.
    for (float scale : {0.0f, -1.0f, NAN, INFINITY}) {
        std::vector<std::uint32_t> out(1, 7u);
        encodeSharedExponents(std::vector<glm::vec3>{glm::vec3(1.0f)}, scale, out);
        EXPECT_EQ(out[0], reference::encodeSharedExponent(glm::vec3(1.0f), scale));
    }
}

TEST(QuantizeFast, SrgbDecodingMatchesTheReferenceForEveryCode) {
    std::vector<std::uint32_t> triples;
    for (std::uint32_t c = 0; c < 256; ++c) {
        EXPECT_EQ(bitsOf(decodeSrgb8(std::uint8_t(c))), bitsOf(reference::decodeSrgb8(c)));
        triples.push_back(c | (255 - c) << 8 | ((c * 7) & 0xFF) << 16);
    }
    std::vector<glm::vec3> fast(triples.size());
    decodeSrgb8Triples(triples, fast);
    for (std::size_t i = 0; i < triples.size(); ++i) {
        const std::uint32_t w = triples[i];
        EXPECT_TRUE(sameBits(
            fast[i], {reference::decodeSrgb8(w & 0xFF), reference::decodeSrgb8((w >> 8) & 0xFF),
                      reference::decodeSrgb8((w >> 16) & 0xFF)}));
    }
}

/// The smallest float in [0, 1] whose reference code is at least c (the code is monotonic).
float srgbThreshold(int c) {
    std::uint32_t below = 0, at = bitsOf(1.0f);
    while (at - below > 1) {
        const std::uint32_t mid = below + (at - below) / 2;
        (reference::encodeSrgb8(std::bit_cast<float>(mid)) >= c ? at : below) = mid;
    }
    return std::bit_cast<float>(at);
}

TEST(QuantizeFast, SrgbEncodingMatchesTheReference) {
    // Every float within 2048 steps of each of the 255 places where the code steps up, where a
    // table could be off by one; then random values and the special ones.
    std::vector<float> values;
    for (int c = 1; c <= 255; ++c) {
        const std::uint32_t t = bitsOf(srgbThreshold(c));
        for (std::uint32_t b = t - 2048; b <= std::min(t + 2048, bitsOf(1.0f)); ++b)
            values.push_back(std::bit_cast<float>(b));
    }
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), octaves(-30.0f, 0.5f);
    for (int i = 0; i < 500000; ++i) {
        values.push_back(unit(rng));
        values.push_back(std::exp2(octaves(rng)));
    }
    for (float v : {0.0f, -0.0f, -1.0f, NAN, -NAN, INFINITY, -INFINITY, 1.0f, 1.5f, FLT_MAX,
                    FLT_MIN, 1e-45f, 0x1p-13f, std::nextafter(0x1p-13f, 0.0f),
                    std::nextafter(1.0f, 0.0f), 0.0031308f, 0.04045f / 12.92f})
        values.push_back(v);
    while (values.size() % 3 != 0) values.push_back(0.5f);

    for (float v : values) ASSERT_EQ(encodeSrgb8(v), reference::encodeSrgb8(v)) << v;
    const std::size_t pixels = values.size() / 3;
    const std::span<const glm::vec3> in(reinterpret_cast<const glm::vec3*>(values.data()), pixels);
    std::vector<std::uint32_t> fast(pixels);
    encodeSrgb8Triples(in, fast);
    for (std::size_t i = 0; i < pixels; ++i)
        ASSERT_EQ(fast[i], std::uint32_t{reference::encodeSrgb8(in[i].x)} |
                               std::uint32_t{reference::encodeSrgb8(in[i].y)} << 8 |
                               std::uint32_t{reference::encodeSrgb8(in[i].z)} << 16);
}

TEST(QuantizeFast, OctNormalDecodingMatchesTheReferenceForEveryCode) {
    std::vector<std::uint32_t> codes(65536);
    for (std::uint32_t c = 0; c < 65536; ++c) codes[c] = c;
    std::vector<glm::vec3> fast(codes.size());
    decodeOctNormals(codes, fast);
    for (std::uint32_t c = 0; c < 65536; ++c) {
        const OctCode code{std::uint8_t(c & 0xFF), std::uint8_t(c >> 8)};
        const glm::vec3 expected = reference::decodeOctNormal(code);
        ASSERT_TRUE(sameBits(fast[c], expected)) << "code " << c;
        ASSERT_TRUE(sameBits(decodeOctNormal(code), expected)) << "code " << c;
    }
}

TEST(QuantizeFast, OctNormalEncodingMatchesTheReference) {
    std::mt19937 rng(13);
    std::normal_distribution<float> g;
    std::uniform_real_distribution<float> decades(-10.0f, 10.0f);
    std::uniform_int_distribution<int> repeats(1, 3);
    std::vector<glm::vec3> normals;
    for (int i = 0; i < 400000; ++i) {
        glm::vec3 n(g(rng), g(rng), g(rng));
        if (i % 2 == 0) n = glm::normalize(n);
        if (i % 5 == 0) n *= std::pow(10.0f, decades(rng));
        // Runs of equal values, as on flat surfaces, which the encoder does not recompute.
        for (int r = repeats(rng); r > 0; --r) normals.push_back(n);
    }
    for (glm::vec3 n :
         {glm::vec3(0.0f), glm::vec3(-0.0f, 0.0f, 0.0f), glm::vec3(0.0f, 0.0f, -1.0f),
          glm::vec3(-0.0f, 0.0f, -1.0f), glm::vec3(0.0f, -0.0f, -1.0f), glm::vec3(0, 0, 1),
          glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, -1, 0),
          glm::vec3(1, 1, 0), glm::vec3(1, -1, -1e-7f), glm::vec3(NAN), glm::vec3(1, NAN, 0),
          glm::vec3(INFINITY, 0, 0), glm::vec3(FLT_MAX, FLT_MAX, 1.0f), glm::vec3(1e-30f),
          glm::vec3(1e-21f, 0, 0), glm::vec3(1e-44f, 1e-44f, -1e-44f)})
        normals.push_back(n);
    std::vector<std::uint32_t> fast(normals.size());
    encodeOctNormals(normals, fast);
    for (std::size_t i = 0; i < normals.size(); ++i) {
        const OctCode expected = reference::encodeOctNormal(normals[i]);
        const glm::vec3 n = normals[i];
        ASSERT_EQ(fast[i], expected.u | std::uint32_t{expected.v} << 8)
            << n.x << " " << n.y << " " << n.z;
        ASSERT_EQ(encodeOctNormal(n), expected);
    }
}

const std::vector<float> kDepthReferences = {1e-6f, 0.37f, 1.0f, 5e5f, FLT_MIN, 1e-42f, 3e38f};

TEST(QuantizeFast, LogDepthDecodingMatchesTheReferenceForEveryCode) {
    std::vector<std::uint32_t> codes(65536);
    for (std::uint32_t c = 0; c < 65536; ++c) codes[c] = c;
    for (float d0 : kDepthReferences) {
        SCOPED_TRACE("d0 " + std::to_string(d0));
        std::vector<float> fast(codes.size());
        decodeLogDepths(codes, d0, fast);
        for (std::uint32_t c = 0; c < 65536; ++c) {
            const float expected = reference::decodeLogDepth(std::uint16_t(c), d0);
            ASSERT_EQ(bitsOf(fast[c]), bitsOf(expected)) << "code " << c;
            ASSERT_EQ(bitsOf(decodeLogDepth(std::uint16_t(c), d0)), bitsOf(expected));
        }
    }
}

TEST(QuantizeFast, LogDepthEncodingMatchesTheReference) {
    for (float d0 : kDepthReferences) {
        SCOPED_TRACE("d0 " + std::to_string(d0));
        std::vector<float> depths;
        // Around every boundary between two codes, where the encoder's approximation of log2
        // must give way to the exact path: the float nearest it and its neighbours.
        for (int k = 1; k < 65535; ++k) {
            const float edge = static_cast<float>(d0 * std::exp2((k - 0.5) / 2048.0));
            const std::uint32_t b = bitsOf(edge);
            for (std::uint32_t n = b - 2; n <= b + 2; ++n)
                depths.push_back(std::bit_cast<float>(n));
        }
        std::mt19937 rng(bitsOf(d0));
        std::uniform_real_distribution<double> octaves(-1.0, 34.0);
        for (int i = 0; i < 300000; ++i)
            depths.push_back(static_cast<float>(d0 * std::exp2(octaves(rng))));
        for (float d : {d0, std::nextafter(d0, INFINITY), std::nextafter(d0, 0.0f), 0.0f, -0.0f,
                        -1.0f, NAN, INFINITY, -INFINITY, FLT_MAX, FLT_MIN, 1e-45f, 1e-40f})
            depths.push_back(d);
        std::vector<std::uint32_t> fast(depths.size());
        encodeLogDepths(depths, d0, fast);
        for (std::size_t i = 0; i < depths.size(); ++i) {
            const std::uint16_t expected = reference::encodeLogDepth(depths[i], d0);
            ASSERT_EQ(fast[i], expected) << depths[i];
            ASSERT_EQ(encodeLogDepth(depths[i], d0), expected) << depths[i];
        }
    }
}

}  // namespace
}  // namespace igi::proto
