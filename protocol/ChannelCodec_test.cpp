#include "ChannelCodec.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

#include <glm/geometric.hpp>

#include "Codec.h"
#include "TestMessages.h"

namespace igi::proto {
namespace {

TileChannels roundTrip(const TileChannels& c, std::size_t* bytes = nullptr) {
    std::vector<std::uint8_t> buf;
    ByteWriter out(buf);
    writeTileChannels(out, c);
    if (bytes) *bytes = buf.size();
    ByteReader in(buf, "tile");
    TileChannels d = readTileChannels(in);
    in.expectEnd();
    return d;
}

std::uint32_t sentMask(const TileChannels& c) {
    std::vector<std::uint8_t> buf;
    ByteWriter out(buf);
    writeTileChannels(out, c);
    ByteReader in(buf, "tile");
    in.u32();
    in.u32();
    return in.u32();
}

/// Sum of squared differences over sum of squares.
double relativeMse(const std::vector<glm::vec3>& ref, const std::vector<glm::vec3>& q) {
    double err = 0.0, sum = 0.0;
    for (std::size_t i = 0; i < ref.size(); ++i) {
        const glm::dvec3 d = glm::dvec3(q[i]) - glm::dvec3(ref[i]);
        err += glm::dot(d, d);
        sum += glm::dot(glm::dvec3(ref[i]), glm::dvec3(ref[i]));
    }
    return sum > 0.0 ? err / sum : err;
}

std::vector<glm::vec3> combined(const TileChannels& c) {
    std::vector<glm::vec3> p(c.count);
    for (int i = 0; i < c.count; ++i) p[i] = c.reflectance[i] * c.irradiance[i] + c.unfiltered[i];
    return p;
}

/// A realistic 32 x 32 tile: smooth reflectance, normals and depth; irradiance that is noise
/// around smooth values with a few zeros and a few pixels 1e-6 .. 1e6 times the others;
/// some misses (depth +inf, no normal); sparse unfiltered highlights.
TileChannels realisticTile(float magnitude, std::uint32_t seed, std::vector<bool>* ordinary) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> noise(0.0f, 0.3f);
    std::uniform_real_distribution<float> u(0.0f, 1.0f), decades(-6.0f, 6.0f);
    const int w = 32, n = w * w;
    TileChannels c;
    c.resize(n, kAllChannels);
    if (ordinary) ordinary->assign(n, true);
    for (int i = 0; i < n; ++i) {
        const float x = float(i % w) / w, y = float(i / w) / w;
        const glm::vec3 base = magnitude * glm::vec3(1.0f + 0.5f * std::sin(4 * x + y),
                                                     0.8f + 0.3f * y, 0.6f + 0.2f * x);
        c.irradiance[i] = glm::max(base * (1.0f + noise(rng)), glm::vec3(0.0f));
        const float r = u(rng);
        if (r < 0.02f) {
            c.irradiance[i] = glm::vec3(0.0f);
        } else if (r < 0.05f) {
            c.irradiance[i] *= std::pow(10.0f, decades(rng));
            if (ordinary) (*ordinary)[i] = false;
        }
        c.reflectance[i] =
            glm::vec3(0.6f + 0.2f * x, 0.4f + 0.1f * y, 0.25f) * (0.9f + 0.1f * u(rng));
        c.normal[i] = glm::normalize(glm::vec3(x - 0.5f, 1.0f, 0.3f * y));
        c.depth[i] = 2.0f + 3.0f * x + y;
        if (i % 97 == 5) {  // a miss
            c.depth[i] = INFINITY;
            c.normal[i] = glm::vec3(0.0f);
            c.reflectance[i] = glm::vec3(0.0f);
            c.irradiance[i] = glm::vec3(0.0f);
        }
        if (i % 53 == 0) c.unfiltered[i] = magnitude * glm::vec3(3.0f * u(rng), 2.0f, 1.0f);
    }
    return c;
}

TEST(ChannelCodec, RealisticTilesKeepRelativeMseBelow1e4) {
    for (float magnitude : {1e-12f, 1.0f, 1e12f}) {
        for (std::uint32_t seed = 1; seed <= 5; ++seed) {
            SCOPED_TRACE("magnitude " + std::to_string(magnitude) + " seed " +
                         std::to_string(seed));
            std::vector<bool> ordinary;
            const TileChannels c = realisticTile(magnitude, seed, &ordinary);
            const TileChannels d = roundTrip(c);
            ASSERT_EQ(d.mask(), kAllChannels);
            const double irr = relativeMse(c.irradiance, d.irradiance);
            const double refl = relativeMse(c.reflectance, d.reflectance);
            const double unf = relativeMse(c.unfiltered, d.unfiltered);
            const double pix = relativeMse(combined(c), combined(d));
            // The ordinary pixels alone, up to 1e6 below the tile's brightest.
            std::vector<glm::vec3> a, b;
            for (int i = 0; i < c.count; ++i)
                if (ordinary[i]) {
                    a.push_back(c.irradiance[i]);
                    b.push_back(d.irradiance[i]);
                }
            const double irrOrdinary = relativeMse(a, b);
            if (seed == 1)
                std::cout << "magnitude " << magnitude << ": relative MSE irradiance " << irr
                          << " (ordinary pixels " << irrOrdinary << "), reflectance " << refl
                          << ", unfiltered " << unf << ", pixel " << pix << "\n";
            EXPECT_LT(irr, 1e-4);
            EXPECT_LT(irrOrdinary, 1e-4);
            EXPECT_LT(refl, 1e-4);
            EXPECT_LT(unf, 1e-4);
            EXPECT_LT(pix, 1e-4);
        }
    }
}

TEST(ChannelCodec, DepthAndNormalsKeepTheirBounds) {
    const TileChannels c = realisticTile(1.0f, 2, nullptr);
    const TileChannels d = roundTrip(c);
    double worstDepth = 0.0, worstAngle = 0.0;
    for (int i = 0; i < c.count; ++i) {
        if (std::isinf(c.depth[i])) {
            EXPECT_TRUE(std::isinf(d.depth[i]));
            EXPECT_EQ(d.normal[i], glm::vec3(0.0f));
            continue;
        }
        worstDepth = std::max(worstDepth, std::abs(double(d.depth[i]) - c.depth[i]) / c.depth[i]);
        const double cosine = std::clamp(double(glm::dot(c.normal[i], d.normal[i])), -1.0, 1.0);
        worstAngle = std::max(worstAngle, std::acos(cosine) * 180.0 / M_PI);
    }
    EXPECT_LT(worstDepth, 1e-3);
    EXPECT_LT(worstAngle, 1.0);
}

TEST(ChannelCodec, ZeroPlanesAreLeftOutAndComeBackAsDefaults) {
    TileChannels c = realisticTile(1.0f, 3, nullptr);
    std::size_t full = 0, reduced = 0;
    roundTrip(c, &full);
    EXPECT_EQ(sentMask(c), kAllChannels);
    std::fill(c.unfiltered.begin(), c.unfiltered.end(), glm::vec3(0.0f));
    std::fill(c.depth.begin(), c.depth.end(), INFINITY);
    std::fill(c.normal.begin(), c.normal.end(), glm::vec3(0.0f));
    EXPECT_EQ(sentMask(c), kIrradiance | kReflectance);
    const TileChannels d = roundTrip(c, &reduced);
    EXPECT_LT(reduced, full);
    EXPECT_EQ(d.mask(), kAllChannels);  // the planes exist, filled with their defaults
    for (int i = 0; i < d.count; ++i) {
        EXPECT_EQ(d.unfiltered[i], glm::vec3(0.0f));
        EXPECT_EQ(d.normal[i], glm::vec3(0.0f));
        EXPECT_TRUE(std::isinf(d.depth[i]) && d.depth[i] > 0);
    }
}

TEST(ChannelCodec, DepthAllAtTheReferenceIsNotMistakenForDefault) {
    TileChannels c;
    c.resize(16, kDepth);
    std::fill(c.depth.begin(), c.depth.end(), 4.0f);  // every code is 0, but not +inf
    EXPECT_EQ(sentMask(c), kDepth);
    const TileChannels d = roundTrip(c);
    for (float v : d.depth) EXPECT_EQ(v, 4.0f);
}

TEST(ChannelCodec, MissingPlanesStayMissingAndEmptyTilesWork) {
    TileChannels c;
    c.resize(10, kIrradiance | kDepth);
    c.irradiance[3] = glm::vec3(1, 2, 3);
    c.depth[3] = 7.0f;
    const TileChannels d = roundTrip(c);
    EXPECT_EQ(d.count, 10);
    EXPECT_EQ(d.mask(), kIrradiance | kDepth);
    EXPECT_EQ(d.irradiance[3].z, 3.0f);  // the plane's maximum is exact, the rest within 2^-9
    EXPECT_NEAR(d.irradiance[3].x, 1.0f, 3.0f / 512);
    EXPECT_NEAR(d.irradiance[3].y, 2.0f, 3.0f / 512);
    EXPECT_EQ(d.irradiance[0], glm::vec3(0.0f));
    EXPECT_EQ(d.depth[3], 7.0f);
    EXPECT_TRUE(std::isinf(d.depth[0]));
    const TileChannels e = roundTrip(TileChannels{});
    EXPECT_EQ(e.count, 0);
    EXPECT_EQ(e.mask(), 0u);
}

TEST(ChannelCodec, TypicalTileCompressesToAtMostTenBytesPerPixel) {
    // 32 x 32 pixels of one interleaving cell: smooth reflectance, normals and depth, noisy
    // irradiance, no unfiltered light.
    TileChannels c = test::sampleChannels(1024, 17);
    std::fill(c.unfiltered.begin(), c.unfiltered.end(), glm::vec3(0.0f));
    std::size_t bytes = 0;
    roundTrip(c, &bytes);
    const double perPixel = double(bytes) / c.count;
    std::cout << "typical tile: " << bytes << " bytes for " << c.count << " pixels = " << perPixel
              << " bytes/pixel (as floats: 40, quantized before zstd: "
              << bytesPerPixel(kIrradiance | kReflectance | kNormal | kDepth) << ")\n";
    EXPECT_LE(perPixel, 10.0);
}

TEST(ChannelCodec, EncoderRefusesInconsistentPlanes) {
    TileChannels c;
    c.resize(10, kIrradiance);
    c.depth.resize(9);
    std::vector<std::uint8_t> buf;
    ByteWriter out(buf);
    EXPECT_THROW(writeTileChannels(out, c), ProtocolError);
    c.resize(int(kMaxTilePixels) + 1, 0);
    EXPECT_THROW(writeTileChannels(out, c), ProtocolError);
}

std::vector<std::uint8_t> encoded(const TileChannels& c) {
    std::vector<std::uint8_t> buf;
    ByteWriter out(buf);
    writeTileChannels(out, c);
    return buf;
}

std::string decodeError(const std::vector<std::uint8_t>& bytes) {
    try {
        ByteReader in(bytes, "tile");
        readTileChannels(in);
        in.expectEnd();
    } catch (const ProtocolError& e) {
        return e.what();
    }
    return "(no error)";
}

void setU32(std::vector<std::uint8_t>& b, std::size_t at, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) b[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
}

TEST(ChannelCodec, DecoderValidatesCountMasksReferencesAndSizes) {
    const auto good = encoded(test::sampleChannels(64));
    ASSERT_EQ(decodeError(good), "(no error)");
    auto bad = good;
    setU32(bad, 0, kMaxTilePixels + 1);  // count
    EXPECT_NE(decodeError(bad).find("pixels, the limit"), std::string::npos) << decodeError(bad);
    bad = good;
    setU32(bad, 0, 65);  // count disagrees with the compressed size
    EXPECT_NE(decodeError(bad).find("declares"), std::string::npos) << decodeError(bad);
    bad = good;
    setU32(bad, 4, kAllChannels | (1u << 5));  // planes
    EXPECT_NE(decodeError(bad).find("unknown channel"), std::string::npos) << decodeError(bad);
    bad = good;
    setU32(bad, 4, kAllChannels & ~kNormal);  // sent is no longer a subset
    EXPECT_NE(decodeError(bad).find("subset"), std::string::npos) << decodeError(bad);
    for (float r : {0.0f, -1.0f, NAN, INFINITY}) {
        bad = good;
        setU32(bad, 12, std::bit_cast<std::uint32_t>(r));  // irradiance scale
        EXPECT_NE(decodeError(bad).find("reference"), std::string::npos) << decodeError(bad);
    }
    bad = good;
    bad.back() ^= 0xFF;  // corrupt the zstd frame's last byte
    EXPECT_NE(decodeError(bad), "(no error)");
}

}  // namespace
}  // namespace igi::proto
