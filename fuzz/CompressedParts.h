#pragma once

// The compressed parts of two messages, opened up for fuzz_protocol (and its seed generator).
//
// A SceneData body and a TileResult's planes travel zstd-compressed: a mutated compressed
// frame is nearly always corrupt, so fed as received the decoders behind them (the scene
// bundle, settings, camera and changes; the plane dequantizers) would see little but the seeds.
// These helpers take the uncompressed part from the fuzzer and compress it into a well-formed
// payload, so that every mutation reaches those decoders.

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <optional>
#include <span>
#include <vector>

#include "ByteWriter.h"
#include "ChannelCodec.h"
#include "Compression.h"

namespace igi::proto::fuzz {

using Bytes = std::span<const std::uint8_t>;

/// A SceneData payload whose body is `body`: u64 size, then the zstd frame.
inline std::vector<std::uint8_t> sceneDataPayloadFromBody(Bytes body) {
    std::vector<std::uint8_t> payload;
    ByteWriter out(payload);
    out.u64(body.size());
    zstdCompressAppend(body, 1, payload);
    return payload;
}

/// The planes of a TileResult as the fuzzer gives them: u8 plane mask, u8 sent mask, the f32
/// references the sent planes need (irradiance, depth, unfiltered, glossy), then the raw shuffled
/// plane bytes. The pixel count is what the raw bytes hold; left-over bytes are ignored.
struct TilePlanesInput {
    std::uint32_t planes = 0;
    std::uint32_t sent = 0;
    std::vector<std::uint32_t> referenceBits;
    std::uint32_t count = 0;
    Bytes raw;
};

inline std::optional<TilePlanesInput> parseTilePlanes(Bytes in) {
    if (in.size() < 2) return std::nullopt;
    TilePlanesInput t;
    t.planes = in[0];  // unknown bits are left in: the decoder must refuse them
    t.sent = in[1];
    in = in.subspan(2);
    for (std::uint32_t bit : {kIrradiance, kDepth, kUnfiltered, kGlossy}) {
        if (!(t.sent & bit)) continue;
        if (in.size() < 4) return std::nullopt;
        std::uint32_t v = 0;
        std::memcpy(&v, in.data(), 4);
        t.referenceBits.push_back(v);
        in = in.subspan(4);
    }
    const std::uint32_t perPixel = bytesPerPixel(t.sent);
    if (perPixel == 0) return std::nullopt;
    t.count =
        static_cast<std::uint32_t>(std::min<std::size_t>(in.size() / perPixel, kMaxTilePixels));
    t.raw = in.first(std::size_t{t.count} * perPixel);
    return t;
}

/// A TileResult payload (fixed tile id and statistics) carrying `in`'s planes, or nothing when
/// `in` is too short to name them.
inline std::optional<std::vector<std::uint8_t>> tileResultPayloadFromPlanes(Bytes in) {
    const std::optional<TilePlanesInput> t = parseTilePlanes(in);
    if (!t) return std::nullopt;
    std::vector<std::uint8_t> payload;
    ByteWriter out(payload);
    out.u32(7);                                 // tileId
    for (int i = 0; i < 2; ++i) out.u64(1000);  // rays, shadowRays
    for (int i = 0; i < 3; ++i) out.u32(1);     // vpls, causticPhotons, setsBuilt
    out.f32(0.5f);                              // renderSeconds
    out.u32(t->count);
    out.u32(t->planes);
    out.u32(t->sent);
    for (std::uint32_t bits : t->referenceBits) out.u32(bits);
    out.u32(0);  // the blob's length, filled in below
    const std::size_t at = payload.size();
    zstdCompressAppend(t->raw, 1, payload);
    const std::size_t length = payload.size() - at;
    for (int i = 0; i < 4; ++i) payload[at - 4 + i] = static_cast<std::uint8_t>(length >> (8 * i));
    return payload;
}

}  // namespace igi::proto::fuzz
