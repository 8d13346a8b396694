#include "ChannelCodec.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include "Compression.h"
#include "ProtocolError.h"
#include "Quantize.h"

namespace igi::proto {
namespace {

constexpr int kZstdLevel = 1;  // tiles are many and small: speed over the last few percent

std::string hex(std::uint32_t v) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "0x%x", v);
    return buf;
}

/// Writes `count` words of `bytes` bytes each, byte 0 of every pixel first, then byte 1, ...
void putShuffled(std::vector<std::uint8_t>& raw, const std::vector<std::uint32_t>& words,
                 std::uint32_t bytes) {
    for (std::uint32_t b = 0; b < bytes; ++b)
        for (std::uint32_t w : words) raw.push_back(static_cast<std::uint8_t>(w >> (8 * b)));
}

std::vector<std::uint32_t> getShuffled(std::span<const std::uint8_t> raw, std::size_t& offset,
                                       std::size_t count, std::uint32_t bytes) {
    std::vector<std::uint32_t> words(count, 0);
    for (std::uint32_t b = 0; b < bytes; ++b) {
        for (std::size_t i = 0; i < count; ++i)
            words[i] |= std::uint32_t{raw[offset + i]} << (8 * b);
        offset += count;
    }
    return words;
}

bool allZero(const std::vector<std::uint32_t>& words) {
    return std::all_of(words.begin(), words.end(), [](std::uint32_t w) { return w == 0; });
}

float largestComponent(const std::vector<glm::vec3>& plane) {
    float m = 0.0f;
    for (const glm::vec3& v : plane)
        for (int i = 0; i < 3; ++i)
            if (v[i] > m) m = std::min(v[i], FLT_MAX);  // NaN compares false; +inf is clamped
    return m;
}

float smallestFiniteDepth(const std::vector<float>& depth) {
    float m = INFINITY;
    for (float d : depth)
        if (d > 0.0f && d < m) m = d;
    return std::isfinite(m) ? m : FLT_MIN;  // only invalid depths: any positive reference works
}

void checkPlaneSize(std::size_t size, int count, const char* name) {
    if (size != 0 && size != static_cast<std::size_t>(count))
        throw ProtocolError(std::string("tile ") + name + " plane has " + std::to_string(size) +
                            " entries, expected " + std::to_string(count));
}

/// One plane on the wire: its quantized words (none when the plane is left out because every
/// pixel has the default value) and, for some, a float reference.
struct EncodedPlane {
    std::uint32_t bit = 0;
    std::uint32_t bytes = 0;
    std::vector<std::uint32_t> words;
    bool hasReference = false;
    float reference = 0.0f;
};

EncodedPlane encodeRgbPlane(std::uint32_t bit, const std::vector<glm::vec3>& plane) {
    EncodedPlane p{bit, 4, {}, true, largestComponent(plane)};
    if (p.reference == 0.0f) return p;  // all zero: no words, left out
    p.words.reserve(plane.size());
    for (const glm::vec3& v : plane) p.words.push_back(encodeSharedExponent(v, p.reference));
    if (allZero(p.words)) p.words.clear();
    return p;
}

EncodedPlane encodeReflectance(const std::vector<glm::vec3>& plane) {
    EncodedPlane p{kReflectance, kReflectanceBytes, {}, false, 0.0f};
    for (const glm::vec3& v : plane)
        p.words.push_back(encodeSrgb8(v.x) | encodeSrgb8(v.y) << 8 | encodeSrgb8(v.z) << 16);
    if (allZero(p.words)) p.words.clear();  // all black: left out
    return p;
}

EncodedPlane encodeNormals(const std::vector<glm::vec3>& plane) {
    EncodedPlane p{kNormal, kNormalBytes, {}, false, 0.0f};
    for (const glm::vec3& n : plane) {
        const OctCode c = encodeOctNormal(n);
        p.words.push_back(c.u | std::uint32_t{c.v} << 8);
    }
    if (allZero(p.words)) p.words.clear();  // no normals at all: left out
    return p;
}

EncodedPlane encodeDepth(const std::vector<float>& plane) {
    EncodedPlane p{kDepth, kDepthBytes, {}, true, smallestFiniteDepth(plane)};
    bool anyHit = false;
    for (float d : plane) {
        const std::uint16_t c = encodeLogDepth(d, p.reference);
        anyHit |= c != kDepthInfinite;
        p.words.push_back(c);
    }
    if (!anyHit) p.words.clear();  // all +inf: left out
    return p;
}

float readReference(ByteReader& in, const char* name) {
    const float r = in.f32();
    if (!(r > 0.0f) || !std::isfinite(r))
        in.fail(std::string("tile ") + name + " reference " + std::to_string(r) +
                " is not a finite positive number");
    return r;
}

}  // namespace

std::uint32_t bytesPerPixel(std::uint32_t mask) {
    std::uint32_t n = 0;
    if (mask & kIrradiance) n += kIrradianceBytes;
    if (mask & kReflectance) n += kReflectanceBytes;
    if (mask & kNormal) n += kNormalBytes;
    if (mask & kDepth) n += kDepthBytes;
    if (mask & kUnfiltered) n += kUnfilteredBytes;
    return n;
}

void writeTileChannels(ByteWriter& out, const TileChannels& channels) {
    const int count = channels.count;
    if (count < 0 || static_cast<std::uint32_t>(count) > kMaxTilePixels)
        throw ProtocolError("tile of " + std::to_string(count) + " pixels, the limit is " +
                            std::to_string(kMaxTilePixels));
    checkPlaneSize(channels.irradiance.size(), count, "irradiance");
    checkPlaneSize(channels.reflectance.size(), count, "reflectance");
    checkPlaneSize(channels.normal.size(), count, "normal");
    checkPlaneSize(channels.depth.size(), count, "depth");
    checkPlaneSize(channels.unfiltered.size(), count, "unfiltered");
    const std::uint32_t planes = count == 0 ? 0 : channels.mask();

    // In bit order, which is also the order on the wire.
    std::vector<EncodedPlane> encoded;
    if (planes & kIrradiance) encoded.push_back(encodeRgbPlane(kIrradiance, channels.irradiance));
    if (planes & kReflectance) encoded.push_back(encodeReflectance(channels.reflectance));
    if (planes & kNormal) encoded.push_back(encodeNormals(channels.normal));
    if (planes & kDepth) encoded.push_back(encodeDepth(channels.depth));
    if (planes & kUnfiltered) encoded.push_back(encodeRgbPlane(kUnfiltered, channels.unfiltered));

    std::uint32_t sent = 0;
    for (const EncodedPlane& p : encoded)
        if (!p.words.empty()) sent |= p.bit;

    out.u32(static_cast<std::uint32_t>(count));
    out.u32(planes);
    out.u32(sent);
    for (const EncodedPlane& p : encoded)
        if ((sent & p.bit) && p.hasReference) out.f32(p.reference);
    if (sent == 0) return;

    std::vector<std::uint8_t> raw;
    raw.reserve(std::size_t{bytesPerPixel(sent)} * count);
    for (const EncodedPlane& p : encoded)
        if (sent & p.bit) putShuffled(raw, p.words, p.bytes);
    const std::vector<std::uint8_t> frame = zstdCompress(raw, kZstdLevel);
    out.blob(frame);
}

TileChannels readTileChannels(ByteReader& in) {
    const std::uint32_t count = in.u32();
    const std::uint32_t planes = in.u32();
    const std::uint32_t sent = in.u32();
    if (count > kMaxTilePixels)
        in.fail("tile of " + std::to_string(count) + " pixels, the limit is " +
                std::to_string(kMaxTilePixels));
    if (planes & ~kAllChannels) in.fail("unknown channel bits in mask " + hex(planes));
    if (sent & ~planes)
        in.fail("sent planes " + hex(sent) + " are not a subset of the tile's planes " +
                hex(planes));
    if (count == 0 && planes != 0) in.fail("an empty tile names planes " + hex(planes));

    float irradianceScale = 0, depthMin = 0, unfilteredScale = 0;
    if (sent & kIrradiance) irradianceScale = readReference(in, "irradiance");
    if (sent & kDepth) depthMin = readReference(in, "depth");
    if (sent & kUnfiltered) unfilteredScale = readReference(in, "unfiltered");

    std::vector<std::uint8_t> raw;
    if (sent != 0) {
        // The frame must declare exactly this size, which the count bounds: checked before the
        // planes are allocated.
        const std::size_t rawSize = std::size_t{bytesPerPixel(sent)} * count;
        raw = zstdDecompressExact(in.blob(), rawSize, in.what());
    }
    TileChannels channels;
    channels.resize(static_cast<int>(count), planes);
    std::size_t offset = 0;
    if (sent & kIrradiance) {
        const auto w = getShuffled(raw, offset, count, kIrradianceBytes);
        for (std::uint32_t i = 0; i < count; ++i)
            channels.irradiance[i] = decodeSharedExponent(w[i], irradianceScale);
    }
    if (sent & kReflectance) {
        const auto w = getShuffled(raw, offset, count, kReflectanceBytes);
        for (std::uint32_t i = 0; i < count; ++i)
            channels.reflectance[i] = {decodeSrgb8(w[i] & 0xFF), decodeSrgb8((w[i] >> 8) & 0xFF),
                                       decodeSrgb8((w[i] >> 16) & 0xFF)};
    }
    if (sent & kNormal) {
        const auto w = getShuffled(raw, offset, count, kNormalBytes);
        for (std::uint32_t i = 0; i < count; ++i)
            channels.normal[i] = decodeOctNormal(
                {static_cast<std::uint8_t>(w[i] & 0xFF), static_cast<std::uint8_t>(w[i] >> 8)});
    }
    if (sent & kDepth) {
        const auto w = getShuffled(raw, offset, count, kDepthBytes);
        for (std::uint32_t i = 0; i < count; ++i)
            channels.depth[i] = decodeLogDepth(static_cast<std::uint16_t>(w[i]), depthMin);
    }
    if (sent & kUnfiltered) {
        const auto w = getShuffled(raw, offset, count, kUnfilteredBytes);
        for (std::uint32_t i = 0; i < count; ++i)
            channels.unfiltered[i] = decodeSharedExponent(w[i], unfilteredScale);
    }
    return channels;
}

}  // namespace igi::proto
