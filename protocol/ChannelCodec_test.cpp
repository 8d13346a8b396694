#include "ChannelCodec.h"

#include <gtest/gtest.h>

#include <atomic>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <iostream>
#include <random>
#include <thread>

#include <zstd.h>
#include <glm/geometric.hpp>

#include "Codec.h"
#include "Compression.h"
#include "QuantizeReference.h"
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
    for (int i = 0; i < c.count; ++i)
        p[i] = c.reflectance[i] * c.irradiance[i] + c.glossy[i] + c.unfiltered[i];
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
        c.glossy[i] = magnitude * 0.2f * glm::vec3(u(rng), 0.5f, 0.25f);
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
    std::fill(c.glossy.begin(), c.glossy.end(), glm::vec3(0.0f));
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
    setU32(bad, 4, kAllChannels | (1u << 6));  // planes
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

// ---- The codec against a straightforward one built on the reference quantizers ----

namespace plain {

std::uint32_t planeCode(std::uint32_t bit, const TileChannels& c, int i, float reference) {
    switch (bit) {
        case kIrradiance:
            return reference::encodeSharedExponent(c.irradiance[i], reference);
        case kReflectance:
            return reference::encodeSrgb8(c.reflectance[i].x) |
                   reference::encodeSrgb8(c.reflectance[i].y) << 8 |
                   reference::encodeSrgb8(c.reflectance[i].z) << 16;
        case kNormal: {
            const OctCode o = reference::encodeOctNormal(c.normal[i]);
            return o.u | std::uint32_t{o.v} << 8;
        }
        case kDepth:
            return reference::encodeLogDepth(c.depth[i], reference);
        case kUnfiltered:
            return reference::encodeSharedExponent(c.unfiltered[i], reference);
        default:
            return reference::encodeSharedExponent(c.glossy[i], reference);
    }
}

float largest(const std::vector<glm::vec3>& plane) {
    float m = 0.0f;
    for (const glm::vec3& v : plane)
        for (int i = 0; i < 3; ++i)
            if (v[i] > m) m = std::min(v[i], FLT_MAX);
    return m;
}

float smallestDepth(const std::vector<float>& depth) {
    float m = INFINITY;
    for (float d : depth)
        if (d > 0.0f && d < m) m = d;
    return std::isfinite(m) ? m : FLT_MIN;
}

/// writeTileChannels as the format describes it, one pixel and one byte at a time.
std::vector<std::uint8_t> encode(const TileChannels& c) {
    const std::uint32_t planes = c.count == 0 ? 0 : c.mask();
    const std::uint32_t bits[] = {kIrradiance, kReflectance, kNormal, kDepth, kUnfiltered, kGlossy};
    const std::uint32_t bytes[] = {4, 3, 2, 2, 4, 4};
    std::uint32_t sent = 0;
    std::vector<float> references;
    std::vector<std::uint8_t> raw;
    for (int p = 0; p < 6; ++p) {
        if (!(planes & bits[p])) continue;
        const float ref = bits[p] == kIrradiance   ? largest(c.irradiance)
                          : bits[p] == kUnfiltered ? largest(c.unfiltered)
                          : bits[p] == kGlossy     ? largest(c.glossy)
                          : bits[p] == kDepth      ? smallestDepth(c.depth)
                                                   : 0.0f;
        const std::uint32_t none = bits[p] == kDepth ? kDepthInfinite : 0u;
        std::vector<std::uint32_t> words;
        for (int i = 0; i < c.count; ++i) words.push_back(planeCode(bits[p], c, i, ref));
        if (std::all_of(words.begin(), words.end(), [&](std::uint32_t w) { return w == none; }))
            continue;
        sent |= bits[p];
        if (ref != 0.0f) references.push_back(ref);
        for (std::uint32_t b = 0; b < bytes[p]; ++b)
            for (std::uint32_t w : words) raw.push_back(static_cast<std::uint8_t>(w >> (8 * b)));
    }
    std::vector<std::uint8_t> out;
    ByteWriter w(out);
    w.u32(static_cast<std::uint32_t>(c.count));
    w.u32(planes);
    w.u32(sent);
    for (float r : references) w.f32(r);
    if (sent != 0) {
        std::vector<std::uint8_t> frame(ZSTD_compressBound(raw.size()));
        frame.resize(
            ZSTD_compress(frame.data(), frame.size(), raw.data(), raw.size(), kTileZstdLevel));
        w.blob(frame);
    }
    return out;
}

/// readTileChannels as the format describes it, for valid input.
TileChannels decode(const std::vector<std::uint8_t>& bytes) {
    ByteReader in(bytes, "plain");
    const std::uint32_t count = in.u32(), planes = in.u32(), sent = in.u32();
    const float scale = (sent & kIrradiance) ? in.f32() : 0.0f;
    const float d0 = (sent & kDepth) ? in.f32() : 0.0f;
    const float unfilteredScale = (sent & kUnfiltered) ? in.f32() : 0.0f;
    const float glossyScale = (sent & kGlossy) ? in.f32() : 0.0f;
    std::vector<std::uint8_t> raw;
    if (sent != 0) {
        const auto frame = in.blob();
        raw.resize(ZSTD_getFrameContentSize(frame.data(), frame.size()));
        ZSTD_decompress(raw.data(), raw.size(), frame.data(), frame.size());
    }
    TileChannels c;
    c.resize(static_cast<int>(count), planes);
    std::size_t offset = 0;
    auto word = [&](std::uint32_t i, std::uint32_t bytes) {
        std::uint32_t w = 0;
        for (std::uint32_t b = 0; b < bytes; ++b)
            w |= std::uint32_t{raw[offset + b * count + i]} << (8 * b);
        return w;
    };
    if (sent & kIrradiance) {
        for (std::uint32_t i = 0; i < count; ++i)
            c.irradiance[i] = reference::decodeSharedExponent(word(i, 4), scale);
        offset += 4 * count;
    }
    if (sent & kReflectance) {
        for (std::uint32_t i = 0; i < count; ++i) {
            const std::uint32_t w = word(i, 3);
            c.reflectance[i] = {reference::decodeSrgb8(w & 0xFF),
                                reference::decodeSrgb8((w >> 8) & 0xFF),
                                reference::decodeSrgb8(w >> 16)};
        }
        offset += 3 * count;
    }
    if (sent & kNormal) {
        for (std::uint32_t i = 0; i < count; ++i) {
            const std::uint32_t w = word(i, 2);
            c.normal[i] = reference::decodeOctNormal(
                {static_cast<std::uint8_t>(w & 0xFF), static_cast<std::uint8_t>(w >> 8)});
        }
        offset += 2 * count;
    }
    if (sent & kDepth) {
        for (std::uint32_t i = 0; i < count; ++i)
            c.depth[i] = reference::decodeLogDepth(static_cast<std::uint16_t>(word(i, 2)), d0);
        offset += 2 * count;
    }
    if (sent & kUnfiltered) {
        for (std::uint32_t i = 0; i < count; ++i)
            c.unfiltered[i] = reference::decodeSharedExponent(word(i, 4), unfilteredScale);
        offset += 4 * count;
    }
    if (sent & kGlossy)
        for (std::uint32_t i = 0; i < count; ++i)
            c.glossy[i] = reference::decodeSharedExponent(word(i, 4), glossyScale);
    return c;
}

}  // namespace plain

template <typename T>
bool sameBits(const std::vector<T>& a, const std::vector<T>& b) {
    // memcmp must not see the null pointers of empty vectors, even for zero bytes.
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

void expectSameBits(const TileChannels& a, const TileChannels& b) {
    EXPECT_EQ(a.count, b.count);
    EXPECT_TRUE(sameBits(a.irradiance, b.irradiance));
    EXPECT_TRUE(sameBits(a.reflectance, b.reflectance));
    EXPECT_TRUE(sameBits(a.normal, b.normal));
    EXPECT_TRUE(sameBits(a.depth, b.depth));
    EXPECT_TRUE(sameBits(a.unfiltered, b.unfiltered));
    EXPECT_TRUE(sameBits(a.glossy, b.glossy));
}

/// Tiles of every kind: realistic ones at extreme magnitudes, odd sizes, a large one (beyond
/// the codec's 1 MiB of reusable buffers), planes missing or all default, values that are not
/// ordinary (NaN, infinite, negative, subnormal) and a scale small enough for the decoder's
/// double path.
std::vector<TileChannels> variedTiles() {
    std::vector<TileChannels> tiles;
    for (float magnitude : {1e-12f, 1.0f, 1e12f})
        for (std::uint32_t seed : {1u, 2u})
            tiles.push_back(realisticTile(magnitude, seed, nullptr));
    for (int n : {1, 3, 64, 1023, 100000}) tiles.push_back(test::sampleChannels(n, 7));
    TileChannels odd = test::sampleChannels(300, 9);
    odd.irradiance[0] = glm::vec3(NAN, -1.0f, INFINITY);
    odd.irradiance[1] = glm::vec3(1e-44f, 0.0f, -0.0f);
    odd.reflectance[2] = glm::vec3(NAN, 2.0f, -3.0f);
    odd.normal[3] = glm::vec3(NAN);
    odd.normal[4] = glm::vec3(0.0f, 0.0f, -1.0f);
    odd.depth[5] = NAN;
    odd.depth[6] = -2.0f;
    odd.depth[7] = 1e30f;
    tiles.push_back(odd);
    TileChannels tiny = test::sampleChannels(200, 10);
    for (glm::vec3& v : tiny.irradiance) v *= 1e-30f;  // scale below 2^-87
    for (float& d : tiny.depth) d *= 1e-40f;           // subnormal depths
    tiles.push_back(tiny);
    TileChannels defaults = test::sampleChannels(50, 11);
    std::fill(defaults.unfiltered.begin(), defaults.unfiltered.end(), glm::vec3(0.0f));
    std::fill(defaults.depth.begin(), defaults.depth.end(), INFINITY);
    tiles.push_back(defaults);
    TileChannels some;
    some.resize(77, kReflectance | kDepth);
    some.depth[3] = 2.0f;
    tiles.push_back(some);
    tiles.push_back(TileChannels{});
    return tiles;
}

TEST(ChannelCodec, WritesTheBytesOfAPlainEncoderAndReadsTheSameFloats) {
    for (const TileChannels& c : variedTiles()) {
        SCOPED_TRACE("tile of " + std::to_string(c.count) + " pixels, planes " +
                     std::to_string(c.mask()));
        const std::vector<std::uint8_t> bytes = encoded(c);
        ASSERT_EQ(bytes, plain::encode(c));
        ByteReader in(bytes, "tile");
        const TileChannels fast = readTileChannels(in);
        expectSameBits(fast, plain::decode(bytes));
    }
}

TEST(ChannelCodec, ReadsArbitraryCodesAsThePlainDecoderDoes) {
    // Codes no encoder would write (every byte random, octahedral (0, v), ...), in all planes.
    std::mt19937 rng(21);
    for (std::uint32_t count : {1u, 1024u, 5000u}) {
        std::vector<std::uint8_t> raw(count * bytesPerPixel(kAllChannels));
        for (auto& b : raw) b = static_cast<std::uint8_t>(rng());
        std::vector<std::uint8_t> bytes;
        ByteWriter w(bytes);
        w.u32(count);
        w.u32(kAllChannels);
        w.u32(kAllChannels);
        for (float r : {3.5f, 0.25f, 1e-30f, 7.0f}) w.f32(r);
        w.blob(zstdCompress(raw, 1));
        ByteReader in(bytes, "tile");
        expectSameBits(readTileChannels(in), plain::decode(bytes));
    }
}

TEST(ChannelCodec, ThreadsDecodeAndEncodeIndependently) {
    // Per-thread buffers and tables built on first use: several threads at once must each get
    // their own tiles' results.
    const auto tiles = variedTiles();
    std::vector<std::vector<std::uint8_t>> wire;
    for (const TileChannels& c : tiles) wire.push_back(plain::encode(c));
    std::atomic<int> mismatches{0};
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([&, t] {
            for (int round = 0; round < 3; ++round)
                for (std::size_t k = 0; k < tiles.size(); ++k) {
                    const std::size_t i = (k + t) % tiles.size();
                    if (encoded(tiles[i]) != wire[i]) ++mismatches;
                    ByteReader in(wire[i], "tile");
                    const TileChannels d = readTileChannels(in);
                    const TileChannels e = plain::decode(wire[i]);
                    if (!sameBits(d.irradiance, e.irradiance) || !sameBits(d.depth, e.depth) ||
                        !sameBits(d.normal, e.normal))
                        ++mismatches;
                }
        });
    for (auto& t : threads) t.join();
    EXPECT_EQ(mismatches, 0);
}

}  // namespace
}  // namespace igi::proto
