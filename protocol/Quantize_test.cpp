#include "Quantize.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

#include <glm/geometric.hpp>

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

}  // namespace
}  // namespace igi::proto
