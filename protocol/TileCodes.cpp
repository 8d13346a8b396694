#include "TileCodes.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "ChannelCodec.h"
#include "Compression.h"

namespace igi::proto {
namespace {

std::string hex(std::uint32_t v) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "0x%x", v);
    return buf;
}

float readReference(ByteReader& in, const char* name) {
    const float r = in.f32();
    if (!(r > 0.0f) || !std::isfinite(r))
        in.fail(std::string("tile ") + name + " reference " + std::to_string(r) +
                " is not a finite positive number");
    return r;
}

}  // namespace

std::size_t TileCodes::rawSize() const {
    return std::size_t{bytesPerPixel(sent)} * count;
}

std::size_t TileCodes::planeOffset(Channel c) const {
    // The sent planes before c, in bit order.
    return std::size_t{bytesPerPixel(sent & (c - 1))} * count;
}

TileCodes readTileCodes(ByteReader& in) {
    TileCodes t;
    t.count = in.u32();
    t.planes = in.u32();
    t.sent = in.u32();
    if (t.count > kMaxTilePixels)
        in.fail("tile of " + std::to_string(t.count) + " pixels, the limit is " +
                std::to_string(kMaxTilePixels));
    if (t.planes & ~kAllChannels) in.fail("unknown channel bits in mask " + hex(t.planes));
    if (t.sent & ~t.planes)
        in.fail("sent planes " + hex(t.sent) + " are not a subset of the tile's planes " +
                hex(t.planes));
    if (t.count == 0 && t.planes != 0) in.fail("an empty tile names planes " + hex(t.planes));

    if (t.sent & kIrradiance) t.irradianceScale = readReference(in, "irradiance");
    if (t.sent & kDepth) t.depthMin = readReference(in, "depth");
    if (t.sent & kUnfiltered) t.unfilteredScale = readReference(in, "unfiltered");
    if (t.sent & kGlossy) t.glossyScale = readReference(in, "glossy");
    if (t.sent != 0) t.compressed = in.blob();
    return t;
}

void decompressPlanes(const TileCodes& codes, std::span<std::uint8_t> out, std::string_view what) {
    // The frame must declare exactly this size, which the count bounds.
    if (codes.sent != 0) zstdDecompressExactTo(codes.compressed, out.first(codes.rawSize()), what);
}

}  // namespace igi::proto
