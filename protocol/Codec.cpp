#include "Codec.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <type_traits>

#include "ByteReader.h"
#include "ByteWriter.h"
#include "ChangeCodec.h"
#include "ChannelCodec.h"
#include "Compression.h"
#include "SceneCodec.h"

namespace igi::proto {
namespace {

// SceneData's fields, in the order of its body: a new field must be added to the codec and to
// docs/PROTOCOL.md, or it silently never reaches the clients.
struct SceneDataFields {
    SceneBundle bundle;
    RenderSettings settings;
    ImageSettings image;
    Camera camera;
    std::vector<SceneChange> changes;
    std::uint32_t baseFirstFrame;
    std::vector<EpochChanges> history;
};
static_assert(sizeof(SceneData) == sizeof(SceneDataFields), "SceneData changed: update Codec.cpp");

constexpr int kSceneZstdLevel = 3;
constexpr std::uint32_t kMaxThreads = 1u << 16;
constexpr std::uint16_t kMaxInterleaveIndex = 64;

ProtocolError oversized(std::size_t size, MessageType type) {
    return ProtocolError("payload of " + std::to_string(size) + " bytes exceeds the " +
                         std::to_string(maxPayloadSize(type)) + "-byte limit for " +
                         messageTypeName(type));
}

float readSeconds(ByteReader& in, const char* name) {
    const float s = in.f32();
    if (!(s >= 0.0f) || !std::isfinite(s))
        in.fail(std::string(name) + " is " + std::to_string(s) + ", expected finite and >= 0");
    return s;
}

// ---- encoders: one per message ----

void writeProof(ByteWriter& out, const std::optional<AuthBytes>& proof) {
    out.u8(proof ? 1 : 0);
    if (proof) out.bytes(*proof);
}

void write(ByteWriter& out, const Hello& m) {
    out.u16(m.protocolVersion);
    out.string(m.buildId);
    out.u32(m.threads);
    out.string(m.hostname);
    out.bytes(m.nonce);
    writeProof(out, m.proof);
}

void write(ByteWriter& out, const Welcome& m) {
    out.u32(m.clientId);
    out.u64(m.sessionSeed);
    writeProof(out, m.proof);
}

void write(ByteWriter& out, const Challenge& m) {
    out.u16(m.protocolVersion);
    out.string(m.buildId);
    out.u8(m.secretRequired ? 1 : 0);
    out.bytes(m.nonce);
}

void write(ByteWriter& out, const SceneData& m) {
    std::vector<std::uint8_t> body;
    ByteWriter b(body);
    writeSceneBundle(b, m.bundle);
    writeRenderSettings(b, m.settings);
    writeImageSettings(b, m.image);
    writeCamera(b, m.camera);
    writeSceneChanges(b, m.changes);
    writeSceneHistory(b, m.baseFirstFrame, m.history);
    if (body.size() > kSceneDataBodyLimit)
        throw ProtocolError("SceneData of " + std::to_string(body.size()) + " bytes exceeds the " +
                            std::to_string(kSceneDataBodyLimit) + "-byte limit");
    out.u64(body.size());
    zstdCompressAppend(body, kSceneZstdLevel, out.buffer());
}

void write(ByteWriter& out, const SceneReady& m) {
    out.u64(m.triangles);
    out.f32(m.buildSeconds);
}

void write(ByteWriter& out, const TileAssign& m) {
    out.u32(m.tileId);
    for (std::uint16_t v : {m.x0, m.y0, m.width, m.height, m.kx, m.ky}) out.u16(v);
    out.u32(m.accumulation);
}

void write(ByteWriter& out, const TileResult& m) {
    out.u32(m.tileId);
    out.u64(m.stats.rays);
    out.u64(m.stats.shadowRays);
    out.u32(m.stats.vpls);
    out.u32(m.stats.causticPhotons);
    out.u32(m.stats.setsBuilt);
    out.f32(m.stats.renderSeconds);
    writeTileChannels(out, m.channels);
}

void write(ByteWriter& out, const SceneUpdate& m) {
    writeSceneChanges(out, m.changes);
}

void write(ByteWriter&, const Heartbeat&) {}
void write(ByteWriter&, const Shutdown&) {}
void write(ByteWriter& out, const Error& m) {
    out.string(m.reason);
}

// ---- decoders: one per message ----

AuthBytes readAuthBytes(ByteReader& in) {
    AuthBytes b;
    const auto raw = in.bytes(b.size());
    std::copy(raw.begin(), raw.end(), b.begin());
    return b;
}

std::optional<AuthBytes> readProof(ByteReader& in) {
    const std::uint8_t present = in.u8();
    if (present > 1) in.fail("proof flag is " + std::to_string(present) + ", expected 0 or 1");
    if (!present) return std::nullopt;
    return readAuthBytes(in);
}

Hello readHello(ByteReader& in) {
    Hello m;
    m.protocolVersion = in.u16();
    m.buildId = in.string();
    m.threads = in.u32();
    if (m.threads > kMaxThreads)
        in.fail("threads is " + std::to_string(m.threads) + ", expected at most " +
                std::to_string(kMaxThreads));
    m.hostname = in.string();
    m.nonce = readAuthBytes(in);
    m.proof = readProof(in);
    return m;
}

Welcome readWelcome(ByteReader& in) {
    Welcome m;
    m.clientId = in.u32();
    m.sessionSeed = in.u64();
    m.proof = readProof(in);
    return m;
}

Challenge readChallenge(ByteReader& in) {
    Challenge m;
    m.protocolVersion = in.u16();
    m.buildId = in.string();
    const std::uint8_t required = in.u8();
    if (required > 1)
        in.fail("secretRequired is " + std::to_string(required) + ", expected 0 or 1");
    m.secretRequired = required == 1;
    m.nonce = readAuthBytes(in);
    return m;
}

SceneData readSceneData(ByteReader& in) {
    const std::uint64_t bodySize = in.u64();
    if (bodySize > kSceneDataBodyLimit)
        in.fail("uncompressed size " + std::to_string(bodySize) + " exceeds the " +
                std::to_string(kSceneDataBodyLimit) + "-byte limit");
    const std::vector<std::uint8_t> body = zstdDecompressExact(
        in.bytes(in.remaining()), static_cast<std::size_t>(bodySize), in.what());
    ByteReader b(body, "SceneData body");
    SceneData m;
    m.bundle = readSceneBundle(b);
    m.settings = readRenderSettings(b);
    m.image = readImageSettings(b);
    m.camera = readCamera(b);
    m.changes = readSceneChanges(b);
    m.history = readSceneHistory(b, m.baseFirstFrame);
    b.expectEnd();
    return m;
}

SceneReady readSceneReady(ByteReader& in) {
    SceneReady m;
    m.triangles = in.u64();
    m.buildSeconds = readSeconds(in, "buildSeconds");
    return m;
}

TileAssign readTileAssign(ByteReader& in) {
    TileAssign m;
    m.tileId = in.u32();
    m.x0 = in.u16();
    m.y0 = in.u16();
    m.width = in.u16();
    m.height = in.u16();
    m.kx = in.u16();
    m.ky = in.u16();
    m.accumulation = in.u32();
    if (m.width == 0 || m.height == 0)
        in.fail("empty region " + std::to_string(m.width) + " x " + std::to_string(m.height));
    if (std::uint32_t{m.x0} + m.width > 65535 || std::uint32_t{m.y0} + m.height > 65535)
        in.fail("region runs past pixel 65535");
    if (m.kx >= kMaxInterleaveIndex || m.ky >= kMaxInterleaveIndex)
        in.fail("interleave cell (" + std::to_string(m.kx) + ", " + std::to_string(m.ky) +
                ") out of range 0 .. " + std::to_string(kMaxInterleaveIndex - 1));
    return m;
}

/// The fields of a TileResult before its channels.
void readTileResultHead(ByteReader& in, std::uint32_t& tileId, TileStats& stats) {
    tileId = in.u32();
    stats.rays = in.u64();
    stats.shadowRays = in.u64();
    stats.vpls = in.u32();
    stats.causticPhotons = in.u32();
    stats.setsBuilt = in.u32();
    stats.renderSeconds = readSeconds(in, "renderSeconds");
}

TileResult readTileResult(ByteReader& in) {
    TileResult m;
    readTileResultHead(in, m.tileId, m.stats);
    m.channels = readTileChannels(in);
    return m;
}

SceneUpdate readSceneUpdate(ByteReader& in) {
    return SceneUpdate{readSceneChanges(in)};
}

Error readError(ByteReader& in) {
    return Error{in.string()};
}

/// Appends the message's payload to `bytes`; throws if it exceeds its type's limit.
void appendPayload(std::vector<std::uint8_t>& bytes, const Message& message) {
    const std::size_t start = bytes.size();
    ByteWriter out(bytes);
    std::visit([&](const auto& m) { write(out, m); }, message);
    const std::size_t size = bytes.size() - start;
    if (size > maxPayloadSize(typeOf(message))) throw oversized(size, typeOf(message));
}

}  // namespace

std::uint32_t maxPayloadSize(MessageType type) {
    switch (type) {
        case MessageType::Hello:
        case MessageType::Welcome:
        case MessageType::SceneReady:
        case MessageType::TileAssign:
        case MessageType::Challenge:
            return kSmallPayloadLimit;
        case MessageType::Heartbeat:
        case MessageType::Shutdown:
            return 0;
        case MessageType::Error:
            return kErrorPayloadLimit;
        case MessageType::TileResult:
            return kTileResultPayloadLimit;
        case MessageType::SceneData:
            return kSceneDataPayloadLimit;
        case MessageType::SceneUpdate:
            return kSceneUpdatePayloadLimit;
    }
    return 0;
}

bool isKnownType(std::uint16_t type) {
    return type >= static_cast<std::uint16_t>(MessageType::Hello) &&
           type <= static_cast<std::uint16_t>(MessageType::Challenge);
}

std::string messageTypeName(MessageType type) {
    switch (type) {
        case MessageType::Hello:
            return "Hello";
        case MessageType::Welcome:
            return "Welcome";
        case MessageType::SceneData:
            return "SceneData";
        case MessageType::SceneReady:
            return "SceneReady";
        case MessageType::TileAssign:
            return "TileAssign";
        case MessageType::TileResult:
            return "TileResult";
        case MessageType::Heartbeat:
            return "Heartbeat";
        case MessageType::Shutdown:
            return "Shutdown";
        case MessageType::Error:
            return "Error";
        case MessageType::SceneUpdate:
            return "SceneUpdate";
        case MessageType::Challenge:
            return "Challenge";
    }
    return "type " + std::to_string(static_cast<unsigned>(type));
}

MessageType typeOf(const Message& message) {
    // The variant's alternatives are declared in the order of the type numbers.
    static_assert(std::variant_size_v<Message> == 11);
    static_assert(std::is_same_v<std::variant_alternative_t<10, Message>, Challenge>);
    return static_cast<MessageType>(message.index() + 1);
}

std::array<std::uint8_t, kHeaderSize> encodeHeader(const Header& header) {
    std::vector<std::uint8_t> bytes;
    ByteWriter out(bytes);
    out.u32(kMagic);
    out.u16(header.version);
    out.u16(static_cast<std::uint16_t>(header.type));
    out.u32(header.frame);
    out.u32(header.epoch);
    out.u32(header.payloadSize);
    out.u32(0);  // reserved
    std::array<std::uint8_t, kHeaderSize> result;
    std::copy(bytes.begin(), bytes.end(), result.begin());
    return result;
}

Header decodeHeader(std::span<const std::uint8_t, kHeaderSize> bytes) {
    ByteReader in(bytes, "header");
    const std::uint32_t magic = in.u32();
    if (magic != kMagic) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "bad magic 0x%08x (expected 0x%08x, \"IGIP\")", magic,
                      kMagic);
        throw ProtocolError(buf);
    }
    Header h;
    h.version = in.u16();
    if (h.version != kVersion)
        throw ProtocolError("protocol version " + std::to_string(h.version) +
                            ", this build speaks " + std::to_string(kVersion));
    const std::uint16_t type = in.u16();
    if (!isKnownType(type)) throw ProtocolError("unknown message type " + std::to_string(type));
    h.type = static_cast<MessageType>(type);
    h.frame = in.u32();
    h.epoch = in.u32();
    h.payloadSize = in.u32();
    const std::uint32_t reserved = in.u32();
    if (reserved != 0)
        throw ProtocolError("reserved header word is " + std::to_string(reserved) + ", expected 0");
    if (h.payloadSize > maxPayloadSize(h.type)) throw oversized(h.payloadSize, h.type);
    return h;
}

std::vector<std::uint8_t> encodePayload(const Message& message) {
    std::vector<std::uint8_t> payload;
    appendPayload(payload, message);
    return payload;
}

std::vector<std::uint8_t> encodeMessage(const Message& message, std::uint32_t frame,
                                        std::uint32_t epoch) {
    // The payload is written in place behind room for the header, which is filled in last:
    // a scene of a gigabyte is not copied once more.
    std::vector<std::uint8_t> bytes(kHeaderSize);
    appendPayload(bytes, message);
    Header h;
    h.type = typeOf(message);
    h.frame = frame;
    h.epoch = epoch;
    h.payloadSize = static_cast<std::uint32_t>(bytes.size() - kHeaderSize);
    const auto header = encodeHeader(h);
    std::copy(header.begin(), header.end(), bytes.begin());
    return bytes;
}

namespace {

/// The checks of every payload before its fields are read.
void checkPayload(const Header& header, std::span<const std::uint8_t> payload,
                  const std::string& name) {
    if (!isKnownType(static_cast<std::uint16_t>(header.type)))
        throw ProtocolError("unknown message " + name);
    if (payload.size() != header.payloadSize)
        throw ProtocolError(name + " payload has " + std::to_string(payload.size()) +
                            " bytes, the header says " + std::to_string(header.payloadSize));
    if (payload.size() > maxPayloadSize(header.type)) throw oversized(payload.size(), header.type);
}

}  // namespace

Message decodeMessage(const Header& header, std::span<const std::uint8_t> payload) {
    const std::string name = messageTypeName(header.type);
    checkPayload(header, payload, name);
    ByteReader in(payload, name);
    Message m;
    switch (header.type) {
        case MessageType::Hello:
            m = readHello(in);
            break;
        case MessageType::Welcome:
            m = readWelcome(in);
            break;
        case MessageType::SceneData:
            m = readSceneData(in);
            break;
        case MessageType::SceneReady:
            m = readSceneReady(in);
            break;
        case MessageType::TileAssign:
            m = readTileAssign(in);
            break;
        case MessageType::TileResult:
            m = readTileResult(in);
            break;
        case MessageType::Heartbeat:
            m = Heartbeat{};
            break;
        case MessageType::Shutdown:
            m = Shutdown{};
            break;
        case MessageType::Error:
            m = readError(in);
            break;
        case MessageType::SceneUpdate:
            m = readSceneUpdate(in);
            break;
        case MessageType::Challenge:
            m = readChallenge(in);
            break;
    }
    in.expectEnd();
    return m;
}

void setHeaderFrameAndEpoch(std::vector<std::uint8_t>& message, std::uint32_t frame,
                            std::uint32_t epoch) {
    if (message.size() < kHeaderSize)
        throw ProtocolError("not an encoded message: shorter than a header");
    for (int i = 0; i < 4; ++i) {
        message[8 + i] = std::uint8_t(frame >> (8 * i));
        message[12 + i] = std::uint8_t(epoch >> (8 * i));
    }
}

TileResultCodes decodeTileResultCodes(const Header& header, std::span<const std::uint8_t> payload) {
    const std::string name = messageTypeName(header.type);
    checkPayload(header, payload, name);
    if (header.type != MessageType::TileResult)
        throw ProtocolError(name + " where a TileResult was expected");
    ByteReader in(payload, name);
    TileResultCodes m;
    readTileResultHead(in, m.tileId, m.stats);
    m.codes = readTileCodes(in);
    in.expectEnd();
    return m;
}

std::uint32_t peekTileId(std::span<const std::uint8_t> payload) {
    ByteReader in(payload, "TileResult");
    return in.u32();
}

}  // namespace igi::proto
