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

const std::uint8_t* TileCodes::bytes(Channel c) const {
    if (!(sent & c)) return nullptr;
    // The planes before c, in bit order, each bytesPerPixel * count bytes.
    return raw.data() + std::size_t{bytesPerPixel(sent & (c - 1))} * count;
}

TileCodes readTileCodes(ByteReader& in, std::vector<std::uint8_t>& raw) {
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

    raw.clear();
    if (t.sent != 0) {
        // The frame must declare exactly this size, which the count bounds: checked before the
        // planes are allocated.
        const std::size_t rawSize = std::size_t{bytesPerPixel(t.sent)} * t.count;
        zstdDecompressExactInto(in.blob(), rawSize, in.what(), raw);
    }
    t.raw = raw;
    return t;
}

}  // namespace igi::proto
