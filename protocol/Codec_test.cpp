#include "Codec.h"

#include <gtest/gtest.h>

#include <cstring>
#include <iostream>
#include <random>

#include "ByteWriter.h"
#include "ChangeCodec.h"
#include "ChannelCodec.h"
#include "Compression.h"
#include "SceneCodec.h"
#include "TestMessages.h"

namespace igi::proto {
namespace {

using test::sampleMessages;

// ---- field-by-field comparison ----

void expectSame(const Hello& a, const Hello& b) {
    EXPECT_EQ(a.protocolVersion, b.protocolVersion);
    EXPECT_EQ(a.buildId, b.buildId);
    EXPECT_EQ(a.threads, b.threads);
    EXPECT_EQ(a.hostname, b.hostname);
    EXPECT_EQ(a.nonce, b.nonce);
    EXPECT_EQ(a.proof, b.proof);
}
void expectSame(const Welcome& a, const Welcome& b) {
    EXPECT_EQ(a.clientId, b.clientId);
    EXPECT_EQ(a.sessionSeed, b.sessionSeed);
    EXPECT_EQ(a.proof, b.proof);
}
void expectSame(const Challenge& a, const Challenge& b) {
    EXPECT_EQ(a.protocolVersion, b.protocolVersion);
    EXPECT_EQ(a.buildId, b.buildId);
    EXPECT_EQ(a.secretRequired, b.secretRequired);
    EXPECT_EQ(a.nonce, b.nonce);
}
void expectSame(const SceneData& a, const SceneData& b) {
    EXPECT_EQ(a.bundle.sceneName, b.bundle.sceneName);
    EXPECT_EQ(a.bundle.sceneText, b.bundle.sceneText);
    EXPECT_EQ(a.bundle.files, b.bundle.files);
    EXPECT_TRUE(a.settings == b.settings);  // RenderSettings' defaulted ==: every field
    EXPECT_EQ(a.image.width, b.image.width);
    EXPECT_EQ(a.image.height, b.image.height);
    EXPECT_EQ(a.image.exposure, b.image.exposure);
    EXPECT_TRUE(a.camera == b.camera);
    EXPECT_EQ(a.changes.size(), b.changes.size());
    EXPECT_TRUE(a.changes == b.changes);  // every field of every change (ChangeCodec_test)
    EXPECT_EQ(a.baseFirstFrame, b.baseFirstFrame);
    EXPECT_TRUE(a.history == b.history);
}
void expectSame(const SceneReady& a, const SceneReady& b) {
    EXPECT_EQ(a.triangles, b.triangles);
    EXPECT_EQ(a.buildSeconds, b.buildSeconds);
}
void expectSame(const TileAssign& a, const TileAssign& b) {
    EXPECT_EQ(a.tileId, b.tileId);
    EXPECT_EQ(a.x0, b.x0);
    EXPECT_EQ(a.y0, b.y0);
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.height, b.height);
    EXPECT_EQ(a.kx, b.kx);
    EXPECT_EQ(a.ky, b.ky);
    EXPECT_EQ(a.accumulation, b.accumulation);
}
void expectNear(glm::vec3 a, glm::vec3 b, float rel) {
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], rel * std::max(1.0f, std::abs(a[i])));
}
void expectSame(const TileResult& a, const TileResult& b) {
    EXPECT_EQ(a.tileId, b.tileId);
    EXPECT_EQ(a.stats.rays, b.stats.rays);
    EXPECT_EQ(a.stats.shadowRays, b.stats.shadowRays);
    EXPECT_EQ(a.stats.vpls, b.stats.vpls);
    EXPECT_EQ(a.stats.causticPhotons, b.stats.causticPhotons);
    EXPECT_EQ(a.stats.setsBuilt, b.stats.setsBuilt);
    EXPECT_EQ(a.stats.renderSeconds, b.stats.renderSeconds);
    // Channels are quantized: their precision is ChannelCodec_test's business; here, that every
    // plane arrives in the right place.
    ASSERT_EQ(a.channels.count, b.channels.count);
    ASSERT_EQ(a.channels.mask(), b.channels.mask());
    for (int i = 0; i < a.channels.count; ++i) {
        expectNear(a.channels.irradiance[i], b.channels.irradiance[i], 0.01f);
        expectNear(a.channels.reflectance[i], b.channels.reflectance[i], 0.01f);
        expectNear(a.channels.normal[i], b.channels.normal[i], 0.02f);
        EXPECT_NEAR(a.channels.depth[i], b.channels.depth[i], 1e-3f * a.channels.depth[i]);
        expectNear(a.channels.unfiltered[i], b.channels.unfiltered[i], 0.01f);
    }
}
void expectSame(const SceneUpdate& a, const SceneUpdate& b) {
    EXPECT_EQ(a.changes.size(), b.changes.size());
    EXPECT_TRUE(a.changes == b.changes);
}
void expectSame(const Heartbeat&, const Heartbeat&) {}
void expectSame(const Shutdown&, const Shutdown&) {}
void expectSame(const Error& a, const Error& b) {
    EXPECT_EQ(a.reason, b.reason);
}

void expectSameMessage(const Message& a, const Message& b) {
    ASSERT_EQ(a.index(), b.index());
    std::visit([&](const auto& x) { expectSame(x, std::get<std::decay_t<decltype(x)>>(b)); }, a);
}

Header headerOf(const std::vector<std::uint8_t>& bytes) {
    return decodeHeader(std::span<const std::uint8_t, kHeaderSize>(bytes.data(), kHeaderSize));
}

std::vector<std::uint8_t> payloadOf(const std::vector<std::uint8_t>& bytes) {
    return {bytes.begin() + kHeaderSize, bytes.end()};
}

/// Decodes `payload` as a message of `type`, from a buffer of exactly its size (so that an
/// out-of-bounds read is a heap overflow AddressSanitizer reports).
Message decodeAs(MessageType type, std::span<const std::uint8_t> payload) {
    Header h;
    h.type = type;
    h.payloadSize = static_cast<std::uint32_t>(payload.size());
    std::vector<std::uint8_t> exact(payload.begin(), payload.end());
    return decodeMessage(h, exact);
}

std::string errorOf(MessageType type, std::span<const std::uint8_t> payload) {
    try {
        decodeAs(type, payload);
    } catch (const ProtocolError& e) {
        return e.what();
    }
    return "(no error)";
}

void writeU32(std::vector<std::uint8_t>& bytes, std::size_t at, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) bytes[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
}

// ---- round trips ----

TEST(Codec, EveryMessageTypeRoundTrips) {
    for (const Message& m : sampleMessages()) {
        SCOPED_TRACE(messageTypeName(typeOf(m)));
        const auto bytes = encodeMessage(m, 1234, 56);
        const Header h = headerOf(bytes);
        EXPECT_EQ(h.version, kVersion);
        EXPECT_EQ(h.type, typeOf(m));
        EXPECT_EQ(h.frame, 1234u);
        EXPECT_EQ(h.epoch, 56u);
        EXPECT_EQ(h.payloadSize, bytes.size() - kHeaderSize);
        expectSameMessage(m, decodeMessage(h, payloadOf(bytes)));
    }
}

TEST(Codec, TypeOfMatchesTheTypeNumbers) {
    EXPECT_EQ(typeOf(Hello{}), MessageType::Hello);
    EXPECT_EQ(typeOf(SceneData{}), MessageType::SceneData);
    EXPECT_EQ(typeOf(TileResult{}), MessageType::TileResult);
    EXPECT_EQ(typeOf(Error{}), MessageType::Error);
    EXPECT_EQ(typeOf(SceneUpdate{}), MessageType::SceneUpdate);
    EXPECT_EQ(static_cast<int>(MessageType::SceneUpdate), 10);
    EXPECT_EQ(messageTypeName(MessageType::SceneUpdate), "SceneUpdate");
}

TEST(Codec, HeaderLayoutIsLittleEndianAsDocumented) {
    const auto bytes = encodeMessage(Heartbeat{}, 0x01020304, 0x0A0B0C0D);
    ASSERT_EQ(bytes.size(), kHeaderSize);
    const std::uint8_t expected[kHeaderSize] = {'I',  'G',  'I',  'P',  14, 0, 7, 0, 4, 3, 2, 1,
                                                0x0D, 0x0C, 0x0B, 0x0A, 0,  0, 0, 0, 0, 0, 0, 0};
    EXPECT_EQ(0, std::memcmp(bytes.data(), expected, kHeaderSize));
}

TEST(Codec, ReencodingDecodedTileIsBitIdentical) {
    // Quantization is idempotent: what the master received re-encodes to the same bytes.
    const auto first = encodePayload(test::sampleTileResult(1000));
    Header h;
    h.type = MessageType::TileResult;
    h.payloadSize = static_cast<std::uint32_t>(first.size());
    const auto second = encodePayload(decodeMessage(h, first));
    EXPECT_EQ(first, second);
}

TEST(Codec, EmptyFieldsRoundTrip) {
    for (const Message& m : {Message(Hello{}), Message(Error{}), Message(TileResult{}),
                             Message(SceneData{}), Message(SceneUpdate{})}) {
        SCOPED_TRACE(messageTypeName(typeOf(m)));
        const auto bytes = encodeMessage(m, 0, 0);
        expectSameMessage(m, decodeMessage(headerOf(bytes), payloadOf(bytes)));
    }
}

// ---- header ----

std::array<std::uint8_t, kHeaderSize> goodHeader(MessageType type = MessageType::Hello,
                                                 std::uint32_t size = 10) {
    Header h;
    h.type = type;
    h.payloadSize = size;
    return encodeHeader(h);
}

std::string headerError(const std::array<std::uint8_t, kHeaderSize>& bytes) {
    try {
        decodeHeader(bytes);
    } catch (const ProtocolError& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(Codec, HeaderRejectsBadMagic) {
    auto h = goodHeader();
    h[0] = 'X';
    EXPECT_NE(headerError(h).find("bad magic"), std::string::npos) << headerError(h);
}

TEST(Codec, HeaderRejectsOtherVersions) {
    auto h = goodHeader();
    h[4] = 1;
    EXPECT_EQ(headerError(h), "protocol version 1, this build speaks 14");
    h[4] = 0;
    EXPECT_NE(headerError(h).find("protocol version 0"), std::string::npos);
}

TEST(Codec, HeaderRejectsUnknownTypes) {
    auto h = goodHeader();
    h[6] = 77;
    EXPECT_EQ(headerError(h), "unknown message type 77");
    h[6] = 0;
    EXPECT_EQ(headerError(h), "unknown message type 0");
    h[6] = 12;
    EXPECT_EQ(headerError(h), "unknown message type 12");
    h[6] = 11;
    EXPECT_EQ(headerError(h), "(no error)");  // Challenge
}

TEST(Codec, HeaderRejectsNonZeroReserved) {
    auto h = goodHeader();
    h[23] = 1;
    EXPECT_NE(headerError(h).find("reserved"), std::string::npos) << headerError(h);
}

TEST(Codec, HeaderRejectsOversizedPayloadPerType) {
    struct Case {
        MessageType type;
        std::uint32_t limit;
    };
    for (Case c :
         {Case{MessageType::Hello, 4096}, Case{MessageType::TileAssign, 4096},
          Case{MessageType::Heartbeat, 0}, Case{MessageType::Shutdown, 0},
          Case{MessageType::Error, 65536}, Case{MessageType::TileResult, 64u << 20},
          Case{MessageType::SceneData, 1u << 30}, Case{MessageType::SceneUpdate, 16u << 20}}) {
        SCOPED_TRACE(messageTypeName(c.type));
        EXPECT_EQ(decodeHeader(goodHeader(c.type, c.limit)).payloadSize, c.limit);
        EXPECT_THROW(decodeHeader(goodHeader(c.type, c.limit + 1)), ProtocolError);
    }
    EXPECT_EQ(headerError(goodHeader(MessageType::TileAssign, 5000000)),
              "payload of 5000000 bytes exceeds the 4096-byte limit for TileAssign");
}

TEST(Codec, HeaderClaimingThreeGigabytesIsRefused) {
    // The header alone is enough to refuse: nothing is read or allocated for the payload.
    const std::uint32_t threeGiB = 3u << 30;
    for (MessageType t : {MessageType::SceneData, MessageType::TileResult, MessageType::Hello,
                          MessageType::SceneUpdate})
        EXPECT_THROW(decodeHeader(goodHeader(t, threeGiB)), ProtocolError);
}

TEST(Codec, PayloadSizeMustMatchTheHeader) {
    const auto bytes = encodeMessage(test::sampleHello(), 0, 0);
    Header h = headerOf(bytes);
    h.payloadSize += 1;
    EXPECT_THROW(decodeMessage(h, payloadOf(bytes)), ProtocolError);
}

TEST(Codec, EncoderRefusesOversizedMessages) {
    Error big{std::string(70000, 'x')};
    EXPECT_THROW(encodeMessage(big, 0, 0), ProtocolError);
    Hello hello = test::sampleHello();
    hello.hostname = std::string(5000, 'h');
    EXPECT_THROW(encodeMessage(hello, 0, 0), ProtocolError);
}

// ---- truncation and trailing bytes ----

TEST(Codec, EveryTruncationThrows) {
    for (const Message& m : sampleMessages()) {
        const MessageType type = typeOf(m);
        SCOPED_TRACE(messageTypeName(type));
        const auto payload = encodePayload(m);
        for (std::size_t n = 0; n < payload.size(); ++n) {
            EXPECT_THROW(decodeAs(type, std::span(payload).first(n)), ProtocolError)
                << "truncated to " << n << " of " << payload.size() << " bytes";
        }
    }
}

TEST(Codec, TruncationNamesTheMessage) {
    const auto payload = encodePayload(test::sampleWelcome());
    EXPECT_EQ(errorOf(MessageType::Welcome, std::span(payload).first(8)),
              "truncated Welcome: needed 4 more bytes at offset 4");
}

TEST(Codec, TrailingBytesThrow) {
    for (const Message& m : sampleMessages()) {
        const MessageType type = typeOf(m);
        SCOPED_TRACE(messageTypeName(type));
        auto payload = encodePayload(m);
        payload.push_back(0);
        EXPECT_THROW(decodeAs(type, payload), ProtocolError);
    }
}

// ---- validation of fields ----

TEST(Codec, TileAssignFieldsAreValidated) {
    auto payload = encodePayload(test::sampleTileAssign());
    EXPECT_NO_THROW(decodeAs(MessageType::TileAssign, payload));
    auto withU16 = [&](std::size_t at, std::uint16_t v) {
        auto p = payload;
        p[at] = v & 0xFF;
        p[at + 1] = v >> 8;
        return errorOf(MessageType::TileAssign, p);
    };
    // Offsets: tileId 0, x0 4, y0 6, width 8, height 10, kx 12, ky 14, accumulation 16.
    EXPECT_NE(withU16(8, 0).find("empty region"), std::string::npos);
    EXPECT_NE(withU16(10, 0).find("empty region"), std::string::npos);
    EXPECT_NE(withU16(12, 64).find("interleave cell"), std::string::npos);
    EXPECT_NE(withU16(14, 64).find("interleave cell"), std::string::npos);
    EXPECT_EQ(withU16(12, 63), "(no error)");
    EXPECT_NE(withU16(4, 65500).find("past pixel"), std::string::npos);
}

TEST(Codec, HelloThreadCountIsValidated) {
    Hello h = test::sampleHello();
    h.threads = 1u << 20;
    EXPECT_NE(errorOf(MessageType::Hello, encodePayload(h)).find("threads"), std::string::npos);
}

TEST(Codec, SecondsMustBeFiniteAndNonNegative) {
    SceneReady r = test::sampleSceneReady();
    for (float bad : {-1.0f, NAN, INFINITY}) {
        r.buildSeconds = bad;
        EXPECT_THROW(decodeAs(MessageType::SceneReady, encodePayload(r)), ProtocolError);
    }
    TileResult t = test::sampleTileResult(4);
    t.stats.renderSeconds = NAN;
    EXPECT_THROW(decodeAs(MessageType::TileResult, encodePayload(t)), ProtocolError);
}

/// A SceneData payload around a body given as bytes (which the encoder would never produce).
std::vector<std::uint8_t> sceneDataPayload(const std::vector<std::uint8_t>& body) {
    std::vector<std::uint8_t> payload;
    ByteWriter out(payload);
    out.u64(body.size());
    out.bytes(zstdCompress(body, 3));
    return payload;
}

/// The uncompressed body of a SceneData, as the encoder lays it out.
std::vector<std::uint8_t> sceneDataBody(const SceneData& m) {
    std::vector<std::uint8_t> body;
    ByteWriter out(body);
    writeSceneBundle(out, m.bundle);
    writeRenderSettings(out, m.settings);
    writeImageSettings(out, m.image);
    writeCamera(out, m.camera);
    writeSceneChanges(out, m.changes);
    writeSceneHistory(out, m.baseFirstFrame, m.history);
    return body;
}

std::string sceneDataError(const SceneData& m) {
    return errorOf(MessageType::SceneData, sceneDataPayload(sceneDataBody(m)));
}

TEST(Codec, SceneDataRangesAreValidated) {
    EXPECT_EQ(sceneDataError(test::sampleSceneData()), "(no error)");
    auto expectRefused = [](const SceneData& m, const std::string& word) {
        const std::string e = sceneDataError(m);
        EXPECT_NE(e.find(word), std::string::npos) << e;
    };
    SceneData m = test::sampleSceneData();
    m.settings.integrator = static_cast<IntegratorKind>(2);
    expectRefused(m, "integrator");
    m = test::sampleSceneData();
    m.settings.interleaveX = 17;
    expectRefused(m, "interleaveX");
    m = test::sampleSceneData();
    m.settings.interleaveY = 0;
    expectRefused(m, "interleaveY");
    m = test::sampleSceneData();
    m.settings.tileSize = 0;
    expectRefused(m, "tileSize");
    m = test::sampleSceneData();
    m.settings.clampDistance = NAN;
    expectRefused(m, "clampDistance");
    m = test::sampleSceneData();
    m.settings.filterNormalThreshold = 1.5f;
    expectRefused(m, "filterNormalThreshold");
    m = test::sampleSceneData();
    m.settings.vplSampling = static_cast<VplSampling>(3);
    expectRefused(m, "unknown VPL sampling 3");
    m = test::sampleSceneData();
    m.settings.vplPool = -2;
    expectRefused(m, "vplPool");
    m = test::sampleSceneData();
    m.image.width = 0;
    expectRefused(m, "width");
    m = test::sampleSceneData();
    m.camera.fovYDeg = 180.0f;
    expectRefused(m, "fovYDeg");
    m = test::sampleSceneData();
    m.camera.position.y = INFINITY;
    expectRefused(m, "position");
    m = test::sampleSceneData();
    m.bundle.files[""] = "x";
    expectRefused(m, "empty path");
    m = test::sampleSceneData();
    std::get<MaterialChange>(m.changes.at(4)).value.ior = -1.0f;
    expectRefused(m, "SceneData body: change 4 (material): ior is -1");
    m = test::sampleSceneData();
    m.history[1].firstFrame = 18;  // epochs begin at increasing frames
    expectRefused(m, "history epoch begins at frame 18, not after 18");
    m = test::sampleSceneData();
    std::get<MaterialChange>(m.history[0].changes.at(4)).value.ior = -1.0f;
    expectRefused(m, "ior is -1");
}

TEST(Codec, SceneDataHistoryCountCannotExceedTheBytesOrTheLimit) {
    for (const std::uint32_t count : {1000u, 0xFFFFFFFFu}) {
        SceneData m = test::sampleSceneData();
        m.history.clear();
        auto body = sceneDataBody(m);
        // The count is the last u32 of a body without history: claim `count` epochs.
        for (int i = 0; i < 4; ++i)
            body[body.size() - 4 + std::size_t(i)] = std::uint8_t(count >> (8 * i));
        const std::string error = errorOf(MessageType::SceneData, sceneDataPayload(body));
        EXPECT_TRUE(error.find("cannot fit") != std::string::npos ||
                    error.find("exceed the limit") != std::string::npos)
            << error;
    }
}

TEST(Codec, SceneDataCarriesItsChangesAtTheEndOfTheBody) {
    // The encoder's body is the documented one: the changes follow the camera.
    const SceneData m = test::sampleSceneData();
    const auto body = sceneDataBody(m);
    const auto payload = encodePayload(m);
    ByteReader in(payload, "test");
    ASSERT_EQ(in.u64(), body.size());
    EXPECT_EQ(zstdDecompressExact(in.bytes(in.remaining()), body.size(), "test"), body);
    const auto decoded = std::get<SceneData>(decodeAs(MessageType::SceneData, payload));
    ASSERT_EQ(decoded.changes.size(), test::sampleChanges().size());
    EXPECT_TRUE(decoded.changes == test::sampleChanges());
}

TEST(Codec, SceneDataBodyTruncatedAnywhereThrows) {
    // Truncating the compressed payload mostly exercises zstd; this cuts the body itself, so
    // every field of the changes at its end is cut somewhere.
    const auto body = sceneDataBody(test::sampleSceneData());
    for (std::size_t n = 0; n < body.size(); ++n) {
        const std::vector<std::uint8_t> cut(body.begin(), body.begin() + n);
        EXPECT_THROW(decodeAs(MessageType::SceneData, sceneDataPayload(cut)), ProtocolError)
            << "body truncated to " << n << " of " << body.size() << " bytes";
    }
}

TEST(Codec, SceneDataFileCountCannotExceedTheBytes) {
    std::vector<std::uint8_t> body;
    ByteWriter out(body);
    out.string("a.json");
    out.string("{}");
    out.u32(0xFFFFFFFF);  // four billion files in a few bytes
    out.u32(0);
    EXPECT_NE(errorOf(MessageType::SceneData, sceneDataPayload(body)).find("cannot fit"),
              std::string::npos);
}

TEST(Codec, SceneDataDuplicateFilesAreRefused) {
    std::vector<std::uint8_t> body;
    ByteWriter out(body);
    out.string("a.json");
    out.string("{}");
    out.u32(2);
    for (int i = 0; i < 2; ++i) {
        out.string("box.obj");
        out.string("v 0 0 0");
    }
    writeRenderSettings(out, RenderSettings{});
    writeImageSettings(out, ImageSettings{});
    writeCamera(out, Camera{});
    out.u32(0);  // no changes
    EXPECT_NE(errorOf(MessageType::SceneData, sceneDataPayload(body)).find("twice"),
              std::string::npos);
}

TEST(Codec, StringLengthBeyondThePayloadIsRefused) {
    std::vector<std::uint8_t> payload;
    ByteWriter out(payload);
    out.u32(0xFFFFFFF0);  // a 4 GiB string in a 6-byte payload: must not be allocated
    out.u16(0);
    EXPECT_NE(errorOf(MessageType::Error, payload).find("truncated Error"), std::string::npos);
}

// ---- zstd bombs in SceneData ----

TEST(Codec, SceneDataDeclaringMoreThanTwoGigabytesIsRefused) {
    auto payload = sceneDataPayload({1, 2, 3});
    for (int i = 0; i < 8; ++i) payload[i] = 0;
    payload[4] = 0xC0;  // 3 << 30 = 3 GiB, little-endian
    EXPECT_NE(errorOf(MessageType::SceneData, payload).find("exceeds"), std::string::npos);
}

TEST(Codec, SceneDataBombIsRefused) {
    // 64 MiB of zeros compress to a few kilobytes; the prefix claims 1000 bytes.
    const std::vector<std::uint8_t> zeros(64u << 20, 0);
    const auto frame = zstdCompress(zeros, 3);
    ASSERT_LT(frame.size(), 64u << 10);
    std::vector<std::uint8_t> payload;
    ByteWriter out(payload);
    out.u64(1000);
    out.bytes(frame);
    EXPECT_NE(errorOf(MessageType::SceneData, payload).find("declares"), std::string::npos);
}

TEST(Codec, SceneDataWhoseFrameLiesAboutItsSizeIsRefused) {
    // A hand-made frame: its header claims 1.5 GiB (within the limit, and the prefix agrees),
    // its one raw block holds 10 bytes. Decoding must fail without allocating 1.5 GiB.
    const std::uint64_t claim = 3ull << 29;
    std::vector<std::uint8_t> payload;
    ByteWriter out(payload);
    out.u64(claim);
    out.u32(0xFD2FB528);  // zstd magic
    out.u8(0xE0);         // 8-byte content size, single segment, no checksum, no dictionary
    out.u64(claim);
    out.u8(0x51);  // last block, raw, 10 bytes
    out.u8(0);
    out.u8(0);
    for (int i = 0; i < 10; ++i) out.u8('a');
    EXPECT_THROW(decodeAs(MessageType::SceneData, payload), ProtocolError);
}

// ---- fuzzing ----

/// Decodes `payload` as `type`; anything but success or ProtocolError is a failure.
/// Returns whether it decoded.
bool decodeMustNotCrash(MessageType type, std::span<const std::uint8_t> payload) {
    try {
        decodeAs(type, payload);
        return true;
    } catch (const ProtocolError&) {
    } catch (const std::exception& e) {
        ADD_FAILURE() << messageTypeName(type) << ": unexpected " << typeid(e).name() << ": "
                      << e.what();
    }
    return false;
}

std::vector<std::uint8_t> mutate(std::vector<std::uint8_t> p, std::mt19937& rng) {
    std::uniform_int_distribution<int> byte(0, 255);
    switch (rng() % 5) {
        case 0: {  // flip a few bytes
            const int flips = 1 + rng() % 4;
            for (int i = 0; i < flips && !p.empty(); ++i) p[rng() % p.size()] = byte(rng);
            break;
        }
        case 1:  // cut
            p.resize(p.empty() ? 0 : rng() % p.size());
            break;
        case 2:  // insert
            p.insert(p.begin() + (p.empty() ? 0 : rng() % p.size()), 1 + rng() % 8,
                     static_cast<std::uint8_t>(byte(rng)));
            break;
        case 3: {  // a length-like field set to something big
            if (p.size() >= 4) {
                const std::size_t at = rng() % (p.size() - 3);
                const std::uint32_t v = (rng() % 2) ? 0xFFFFFFFFu : (rng() % 100000);
                writeU32(p, at, v);
            }
            break;
        }
        default: {  // entirely random
            p.resize(rng() % 64);
            for (auto& b : p) b = static_cast<std::uint8_t>(byte(rng));
        }
    }
    return p;
}

TEST(Codec, FuzzedPayloadsThrowOrDecode) {
    std::mt19937 rng(20020101);
    for (const Message& m : sampleMessages()) {
        const MessageType type = typeOf(m);
        SCOPED_TRACE(messageTypeName(type));
        const auto payload = encodePayload(m);
        int decoded = 0;
        for (int i = 0; i < 3000; ++i) decoded += decodeMustNotCrash(type, mutate(payload, rng));
        std::cout << "fuzz " << messageTypeName(type) << ": " << decoded
                  << " of 3000 mutated payloads decoded, the rest threw ProtocolError\n";
    }
}

TEST(Codec, FuzzedSceneDataBodiesThrowOrDecode) {
    // Mutations of the compressed bytes rarely survive zstd; these reach the body's parser.
    const auto body = sceneDataBody(test::sampleSceneData());
    std::mt19937 rng(7);
    int decoded = 0;
    for (int i = 0; i < 3000; ++i)
        decoded += decodeMustNotCrash(MessageType::SceneData, sceneDataPayload(mutate(body, rng)));
    std::cout << "fuzz SceneData body: " << decoded << " of 3000 decoded\n";
    EXPECT_GT(decoded, 0);  // the mutations reach past the first checks
}

TEST(Codec, FuzzedTileChannelsThrowOrDecode) {
    // Mutate the uncompressed tile layout, then compress it properly, so the channel decoder's
    // own checks are what is exercised.
    const TileResult t = test::sampleTileResult(64);
    const auto payload = encodePayload(t);
    // The tile prefix: 36 bytes of id and stats, then count, planes, sent, four references.
    const std::size_t channelsAt = 36, blobAt = channelsAt + 12 + 16;
    std::vector<std::uint8_t> prefix(payload.begin(), payload.begin() + blobAt);
    std::uint32_t blobSize = 0;
    std::memcpy(&blobSize, payload.data() + blobAt, 4);
    ASSERT_EQ(blobAt + 4 + blobSize, payload.size());
    const auto raw = zstdDecompressExact(std::span(payload).subspan(blobAt + 4),
                                         64 * bytesPerPixel(kAllChannels), "test");
    std::mt19937 rng(11);
    int decoded = 0;
    for (int i = 0; i < 3000; ++i) {
        auto p = (rng() % 2) ? mutate(prefix, rng) : prefix;
        auto r = (rng() % 2) ? mutate(raw, rng) : raw;
        ByteWriter out(p);
        out.blob(zstdCompress(r, 1));
        decoded += decodeMustNotCrash(MessageType::TileResult, p);
    }
    std::cout << "fuzz tile channels: " << decoded << " of 3000 decoded\n";
    EXPECT_GT(decoded, 0);
}

}  // namespace
}  // namespace igi::proto

namespace igi::proto {
namespace {

TEST(Codec, RewritingFrameAndEpochOfAnEncodedMessage) {
    TileResult r;
    r.tileId = 5;
    r.channels.resize(2, kIrradiance);
    auto bytes = encodeMessage(r, 3, 4);
    setHeaderFrameAndEpoch(bytes, 70000, 9);
    const Header h =
        decodeHeader(std::span<const std::uint8_t, kHeaderSize>(bytes.data(), kHeaderSize));
    EXPECT_EQ(h.frame, 70000u);
    EXPECT_EQ(h.epoch, 9u);
    EXPECT_EQ(peekTileId(std::span(bytes).subspan(kHeaderSize)), 5u);
    EXPECT_EQ(std::get<TileResult>(decodeMessage(h, std::span(bytes).subspan(kHeaderSize))).tileId,
              5u);
    EXPECT_THROW(peekTileId(std::span<const std::uint8_t>(bytes.data(), 3)), ProtocolError);
}

}  // namespace
}  // namespace igi::proto

namespace igi::proto {
namespace {

TEST(Codec, HandshakeMessagesWithoutProofsRoundTripAndBadFlagsAreRefused) {
    Hello hello = test::sampleHello();
    hello.proof.reset();
    const auto bytes = encodePayload(hello);
    Header h;
    h.type = MessageType::Hello;
    h.payloadSize = std::uint32_t(bytes.size());
    EXPECT_FALSE(std::get<Hello>(decodeMessage(h, bytes)).proof.has_value());
    auto bad = bytes;
    bad[bad.size() - 1] = 2;  // the proof flag
    EXPECT_THROW(decodeMessage(h, bad), ProtocolError);

    Challenge challenge = test::sampleChallenge();
    auto c = encodePayload(challenge);
    h.type = MessageType::Challenge;
    h.payloadSize = std::uint32_t(c.size());
    c[c.size() - 33] = 7;  // secretRequired
    EXPECT_THROW(decodeMessage(h, c), ProtocolError);
}

}  // namespace
}  // namespace igi::proto
