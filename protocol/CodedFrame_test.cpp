#include "CodedFrame.h"

#include <algorithm>
#include <cstring>
#include <iostream>
#include <optional>
#include <random>
#include <thread>

#include <gtest/gtest.h>

#include "ByteReader.h"
#include "ChannelCodec.h"
#include "Codec.h"
#include "Compression.h"
#include "ProtocolError.h"
#include "Quantize.h"
#include "TestMessages.h"
#include "TestTiles.h"
#include "render/FrameBuffer.h"

namespace igi::proto {
namespace {

struct Shape {
    int width, height, n, m, tileSize;
};

/// The frame the old path assembles from the same bytes: decoded to floats, then scattered.
void scatterFloats(FrameBuffer& f, const std::vector<Tile>& tiles,
                   const std::vector<std::vector<std::uint8_t>>& wire, const Shape& s) {
    for (std::size_t i = 0; i < tiles.size(); ++i) {
        ByteReader in(wire[i], "TileResult");
        f.scatter(tiles[i], s.n, s.m, readTileChannels(in));
    }
}

void scatterCodes(CodedFrame& f, const std::vector<Tile>& tiles,
                  const std::vector<std::vector<std::uint8_t>>& wire, std::mt19937& rng) {
    // In any order: a plane may come to life after tiles that left it out were copied.
    std::vector<std::size_t> order(tiles.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), rng);
    for (std::size_t i : order) {
        ByteReader in(wire[i], "TileResult");
        f.scatter(tiles[i], readTileCodes(in));
    }
}

/// Every row of `coded`, in both instruction sets, against `reference` split in cell order.
void expectSameRows(const CodedFrame& coded, const FrameBuffer& reference, const Shape& s,
                    const std::string& what) {
    const CellOrder order(s.width, s.n);
    FrameRow expected, got;
    std::vector<lanes::Isa> isas = {lanes::Isa::kBaseline};
    if (lanes::hasAvx2()) isas.push_back(lanes::Isa::kAvx2);
    for (int y = 0; y < s.height; ++y) {
        splitRow(reference, y, order, expected);
        for (lanes::Isa isa : isas) {
            coded.decodeRow(y, got, isa);
            ASSERT_EQ(got.y, y);
            for (int p = FrameRow::kDepth; p <= FrameRow::kUb; ++p) {
                const bool glossyPlane = p >= FrameRow::kGr && p <= FrameRow::kGb;
                if (glossyPlane && !coded.live(kGlossy)) {
                    // Not read by the filter; the floats hold zeros there.
                    if (reference.live.has(kGlossy)) {
                        for (int i = 0; i < s.width; ++i) ASSERT_EQ(expected[p][i], 0.0f);
                    }
                    continue;
                }
                for (int i = 0; i < s.width; ++i)
                    ASSERT_EQ(std::memcmp(&got[p][i], &expected[p][i], sizeof(float)), 0)
                        << what << ": row " << y << " plane " << p << " position " << i << ": "
                        << got[p][i] << " vs " << expected[p][i] << " (isa " << int(isa) << ")";
            }
        }
    }
}

// The master copies the tiles' codes and dequantizes rows as it filters them; the floats must
// be bit for bit those of the decoder that dequantizes every tile to floats (readTileChannels)
// and scatters them, over shapes that cut tiles at the image's edges, interleavings of every
// width, planes that come to life in a later frame and go quiet again, and references that
// leave the fast path.
TEST(CodedFrame, RowsEqualTheFloatDecoderScatteredBitForBit) {
    const Shape shapes[] = {{29, 17, 3, 3, 2}, {64, 24, 3, 3, 32}, {13, 9, 1, 1, 4},
                            {37, 11, 4, 2, 3}, {5, 5, 3, 3, 32},   {100, 7, 2, 3, 5}};
    std::mt19937 rng(5);
    for (const Shape& s : shapes) {
        const auto tiles = makeTiles(s.width, s.height, s.n, s.m, s.tileSize);
        CodedFrame buffers[2];
        FrameBuffer reference[2];
        for (int frame = 0; frame < 4; ++frame) {
            test::RandomTiles random;
            if (frame == 1 || frame == 2) random.planes |= kGlossy;
            if (frame == 3) random.planes &= ~kUnfiltered;
            const auto wire = random.encoded(tiles, s.n, s.m, rng);
            CodedFrame& coded = buffers[frame % 2];
            FrameBuffer& floats = reference[frame % 2];
            coded.reuse(s.width, s.height, s.n, s.m, s.tileSize);
            floats.reuse(s.width, s.height);
            scatterCodes(coded, tiles, wire, rng);
            scatterFloats(floats, tiles, wire, s);
            expectSameRows(coded, floats, s,
                           std::to_string(s.width) + "x" + std::to_string(s.height) + " frame " +
                               std::to_string(frame));
        }
    }
}

// A result whose pixel count is not its tile's is refused before it writes anything.
TEST(CodedFrame, RefusesAResultOfAnotherTilesSize) {
    const Shape s{16, 12, 2, 2, 4};
    const auto tiles = makeTiles(s.width, s.height, s.n, s.m, s.tileSize);
    std::mt19937 rng(1);
    const auto wire = test::RandomTiles{}.encoded(tiles, s.n, s.m, rng);
    CodedFrame coded;
    coded.reuse(s.width, s.height, s.n, s.m, s.tileSize);
    ByteReader in(wire[0], "TileResult");
    const TileCodes codes = readTileCodes(in);
    Tile other = tiles[0];
    other.width -= 2;  // a tile with fewer pixels
    ASSERT_NE(other.pixelCount(s.n, s.m), tiles[0].pixelCount(s.n, s.m));
    EXPECT_THROW(coded.scatter(other, codes), ProtocolError);
    EXPECT_FALSE(coded.live(kIrradiance));  // nothing came to life
}

// Tiles of one frame are copied from several threads at once.
TEST(CodedFrame, ThreadsScatterOneFrameTogether) {
    const Shape s{96, 48, 3, 3, 4};
    const auto tiles = makeTiles(s.width, s.height, s.n, s.m, s.tileSize);
    for (int round = 0; round < 5; ++round) {
        std::mt19937 rng{std::uint32_t(round)};
        test::RandomTiles random;
        random.planes |= kGlossy;
        const auto wire = random.encoded(tiles, s.n, s.m, rng);
        CodedFrame coded;
        coded.reuse(s.width, s.height, s.n, s.m, s.tileSize);
        std::vector<std::thread> threads;
        for (int t = 0; t < 4; ++t)
            threads.emplace_back([&, t] {
                for (std::size_t i = std::size_t(t); i < tiles.size(); i += 4) {
                    ByteReader in(wire[i], "TileResult");
                    coded.scatter(tiles[i], readTileCodes(in));
                }
            });
        for (auto& t : threads) t.join();
        FrameBuffer floats;
        floats.reuse(s.width, s.height);
        scatterFloats(floats, tiles, wire, s);
        expectSameRows(coded, floats, s, "round " + std::to_string(round));
    }
}

// Every code of every table plane, and shared exponents of every exponent, against the
// per-value decoders (Quantize.h): one tile of 65536 pixels whose pixel i has depth code i,
// normal code i, sRGB codes i, i >> 8 and i * 7, and a random shared-exponent word, under
// references that take the float and the double paths.
TEST(CodedFrame, DecodesEveryCodeAsThePerValueDecoders) {
    constexpr int kSide = 256, kPixels = kSide * kSide;
    const Shape s{kSide, kSide, 1, 1, kSide};
    const Tile tile = makeTiles(s.width, s.height, s.n, s.m, s.tileSize)[0];
    ASSERT_EQ(tile.pixelCount(1, 1), kPixels);
    std::mt19937 rng(23);
    std::vector<std::uint32_t> irradiance(kPixels), unfiltered(kPixels);
    for (auto& w : irradiance) w = std::uint32_t(rng());
    for (auto& w : unfiltered) w = std::uint32_t(rng());
    // The planes as writeTileChannels lays them out: byte b of every pixel, then byte b + 1.
    std::vector<std::uint8_t> raw;
    auto put = [&](auto code, int bytes) {
        for (int b = 0; b < bytes; ++b)
            for (int i = 0; i < kPixels; ++i) raw.push_back(std::uint8_t(code(i) >> (8 * b)));
    };
    put([&](int i) { return irradiance[std::size_t(i)]; }, 4);
    put(
        [](int i) {
            return std::uint32_t(i & 0xFF) | std::uint32_t((i >> 8) & 0xFF) << 8 |
                   std::uint32_t((i * 7) & 0xFF) << 16;
        },
        3);
    put([](int i) { return std::uint32_t(i); }, 2);  // normal u | v << 8
    put([](int i) { return std::uint32_t(i); }, 2);  // depth
    put([&](int i) { return unfiltered[std::size_t(i)]; }, 4);
    const auto compressed = zstdCompress(raw, 1);
    for (const float scale : {1.0f, 3.5e-30f, 2.5e38f}) {
        TileCodes codes;
        codes.count = kPixels;
        codes.planes = codes.sent = kIrradiance | kReflectance | kNormal | kDepth | kUnfiltered;
        codes.irradianceScale = scale, codes.unfilteredScale = 1.0f / (scale + 1.0f);
        codes.depthMin = scale;
        codes.compressed = compressed;
        ASSERT_EQ(codes.rawSize(), raw.size());
        CodedFrame coded;
        coded.reuse(s.width, s.height, s.n, s.m, s.tileSize);
        coded.scatter(tile, codes);
        std::vector<lanes::Isa> isas = {lanes::Isa::kBaseline};
        if (lanes::hasAvx2()) isas.push_back(lanes::Isa::kAvx2);
        FrameRow row;
        for (const lanes::Isa isa : isas)
            for (int y = 0; y < kSide; ++y) {
                coded.decodeRow(y, row, isa);
                for (int x = 0; x < kSide; ++x) {
                    const int i = y * kSide + x;
                    const glm::vec3 e = decodeSharedExponent(irradiance[std::size_t(i)], scale);
                    const glm::vec3 u =
                        decodeSharedExponent(unfiltered[std::size_t(i)], codes.unfilteredScale);
                    const glm::vec3 n = decodeOctNormal({std::uint8_t(i), std::uint8_t(i >> 8)});
                    const float expected[] = {decodeLogDepth(std::uint16_t(i), scale),
                                              n.x,
                                              n.y,
                                              n.z,
                                              e.x,
                                              e.y,
                                              e.z,
                                              0,
                                              0,
                                              0,
                                              decodeSrgb8(std::uint8_t(i)),
                                              decodeSrgb8(std::uint8_t(i >> 8)),
                                              decodeSrgb8(std::uint8_t(i * 7)),
                                              u.x,
                                              u.y,
                                              u.z};
                    for (int p = 0; p <= FrameRow::kUb; ++p) {
                        if (p >= FrameRow::kGr && p <= FrameRow::kGb) continue;
                        ASSERT_EQ(std::memcmp(&row[p][x], &expected[p], sizeof(float)), 0)
                            << "scale " << scale << " isa " << int(isa) << " pixel " << i
                            << " plane " << p << ": " << row[p][x] << " vs " << expected[p];
                    }
                }
            }
    }
}

std::vector<std::uint8_t> mutate(std::vector<std::uint8_t> p, std::mt19937& rng) {
    if (p.empty()) return p;
    switch (rng() % 3) {
        case 0:  // flip a few bytes
            for (int i = 0, flips = 1 + int(rng() % 4); i < flips; ++i)
                p[rng() % p.size()] = std::uint8_t(rng());
            break;
        case 1:  // cut
            p.resize(rng() % p.size());
            break;
        default:  // insert
            p.insert(p.begin() + long(rng() % p.size()), 1 + rng() % 8, std::uint8_t(rng()));
    }
    return p;
}

// The master's path (decodeTileResultCodes, then CodedFrame::scatter) must refuse exactly the
// tile results that decodeMessage refuses, with a ProtocolError and nothing else, and what it
// accepts must decode to the floats decodeMessage gives: payloads mutated before and after
// compression, in the prefix, the planes and the zstd frame.
TEST(CodedFrame, RefusesWhatTheMessageDecoderRefusesAndReadsTheRestTheSame) {
    const TileResult sample = test::sampleTileResult(64);
    const auto payload = encodePayload(sample);
    const std::size_t blobAt = 36 + 12 + 16;  // id and stats; count, masks; four references
    const std::vector<std::uint8_t> prefix(payload.begin(), payload.begin() + blobAt);
    const auto raw = zstdDecompressExact(std::span(payload).subspan(blobAt + 4),
                                         64 * bytesPerPixel(kAllChannels), "test");
    const Shape s{8, 8, 1, 1, 8};  // one tile of 64 pixels
    const Tile tile = makeTiles(s.width, s.height, s.n, s.m, s.tileSize)[0];
    ASSERT_EQ(tile.pixelCount(s.n, s.m), 64);
    std::mt19937 rng(17);
    int accepted = 0;
    for (int i = 0; i < 3000; ++i) {
        std::vector<std::uint8_t> p = rng() % 2 ? mutate(prefix, rng) : prefix;
        {
            ByteWriter out(p);
            out.blob(zstdCompress(rng() % 2 ? mutate(raw, rng) : raw, 1));
        }
        if (rng() % 4 == 0) p = mutate(p, rng);  // the zstd frame or its length too
        Header h;
        h.type = MessageType::TileResult;
        h.payloadSize = std::uint32_t(p.size());
        std::optional<TileResult> expected;
        try {
            expected = std::get<TileResult>(decodeMessage(h, p));
        } catch (const ProtocolError&) {
        }
        CodedFrame coded;
        coded.reuse(s.width, s.height, s.n, s.m, s.tileSize);
        bool refused = false;
        try {
            coded.scatter(tile, decodeTileResultCodes(h, p).codes);
        } catch (const ProtocolError&) {
            refused = true;
        }
        if (!expected) {
            ASSERT_TRUE(refused) << "mutation " << i << " accepted by the codes' path only";
            continue;
        }
        if (expected->channels.count != 64) {
            ASSERT_TRUE(refused) << "mutation " << i << ": a tile of another size accepted";
            continue;
        }
        ASSERT_FALSE(refused) << "mutation " << i << " refused by the codes' path only";
        ++accepted;
        FrameBuffer floats;
        floats.reuse(s.width, s.height);
        floats.scatter(tile, s.n, s.m, expected->channels);
        expectSameRows(coded, floats, s, "mutation " + std::to_string(i));
    }
    std::cout << "hostile tiles: " << accepted << " of 3000 accepted\n";
    EXPECT_GT(accepted, 100);
}

// Adaptive tiles fill a region a frame leaves out with the cells of the frame that last
// rendered it: after copyRegion, every row reads as a frame whose tiles of that region came
// from the other frame and the rest from its own, bit for bit, references included.
TEST(CodedFrame, CopyRegionTakesTheOtherFramesCellsThere) {
    const Shape shapes[] = {{29, 17, 3, 3, 2}, {37, 11, 4, 2, 3}, {100, 7, 2, 3, 5}};
    std::mt19937 rng(8);
    for (const Shape& s : shapes) {
        const auto tiles = makeTiles(s.width, s.height, s.n, s.m, s.tileSize);
        test::RandomTiles first, second;
        first.extremeScales = true;
        const auto wireA = first.encoded(tiles, s.n, s.m, rng);
        const auto wireB = second.encoded(tiles, s.n, s.m, rng);
        CodedFrame a, b;
        a.reuse(s.width, s.height, s.n, s.m, s.tileSize);
        b.reuse(s.width, s.height, s.n, s.m, s.tileSize);
        scatterCodes(a, tiles, wireA, rng);
        scatterCodes(b, tiles, wireB, rng);
        // Region 1's tiles (those at tiles[0]'s neighbour) from a, the rest from b.
        const int regionWidth = s.n * s.tileSize;
        const Tile region{regionWidth,
                          0,
                          std::min(regionWidth, s.width - regionWidth),
                          std::min(s.m * s.tileSize, s.height),
                          0,
                          0};
        b.copyRegion(a, region);
        std::vector<std::vector<std::uint8_t>> mixed;
        for (std::size_t i = 0; i < tiles.size(); ++i)
            mixed.push_back(tiles[i].x0 == region.x0 && tiles[i].y0 == region.y0 ? wireA[i]
                                                                                 : wireB[i]);
        FrameBuffer floats;
        floats.reuse(s.width, s.height);
        scatterFloats(floats, tiles, mixed, s);
        expectSameRows(b, floats, s, std::to_string(s.width) + "x" + std::to_string(s.height));
        CodedFrame other;
        other.reuse(s.width + 1, s.height, s.n, s.m, s.tileSize);
        EXPECT_THROW(other.copyRegion(a, region), std::logic_error);
    }
}

}  // namespace
}  // namespace igi::proto
