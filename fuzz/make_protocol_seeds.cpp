// Writes the seed corpus of fuzz_protocol, or checks it. The build runs `write` into
// build-fuzz/fuzz/seeds/protocol/ whenever this tool is rebuilt, that is whenever the protocol
// code or protocol/TestMessages.h changes (fuzz/CMakeLists.txt): no seed is committed, so the
// seeds always speak the wire of the checkout.
//
//   make_protocol_seeds write DIR   one file per seed, from protocol/TestMessages.h
//   make_protocol_seeds check DIR   every seed decodes (the ctest test Fuzz.protocol_seeds)
//
// Seeds come in the shapes the fuzz target reads: "<Type>[-variant].msg" is a stream of whole
// messages (header and payload, as on the socket), "<Type>[-variant].payload" is one payload
// alone, "SceneData[-variant].body" and "TileResult[-variant].body" are the uncompressed part
// of one (see CompressedParts.h). A seed the decoder refuses only teaches the fuzzer the refusal
// path, so the check fails when one does: the encoder writes what the decoder refuses, or a
// seed below is built wrong (or DIR holds files from elsewhere).

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <span>
#include <string>
#include <vector>

#include "ByteReader.h"
#include "Codec.h"
#include "CompressedParts.h"
#include "TestMessages.h"

namespace {

namespace fs = std::filesystem;
using namespace igi::proto;
using Bytes = std::vector<std::uint8_t>;

struct Seed {
    std::string name;  // without the extension
    std::vector<Message> messages;
};

/// A tile whose planes are partly left out on the wire: no reflectance (all black), depth only
/// where something was hit.
TileResult sparseTile() {
    TileResult m = test::sampleTileResult(16);
    m.tileId = 5;
    for (auto& r : m.channels.reflectance) r = glm::vec3(0.0f);
    for (std::size_t i = 0; i < m.channels.depth.size(); i += 3) m.channels.depth[i] = INFINITY;
    return m;
}

TileResult emptyTile() {
    TileResult m;
    m.tileId = 6;
    return m;
}

SceneData smallScene() {
    SceneData m = test::sampleSceneData();
    m.bundle.files.erase("tex/wood.png");
    m.changes.clear();
    return m;
}

std::vector<Seed> seeds() {
    std::vector<Seed> out;
    for (const Message& m : test::sampleMessages())
        out.push_back({messageTypeName(typeOf(m)), {m}});
    out.push_back({"TileResult-16", {test::sampleTileResult(16)}});
    out.push_back({"TileResult-sparse", {sparseTile()}});
    out.push_back({"TileResult-empty", {emptyTile()}});
    out.push_back({"SceneData-small", {smallScene()}});
    out.push_back({"SceneUpdate-empty", {SceneUpdate{}}});
    Hello bare;  // empty strings, no optional fields
    bare.threads = 1;
    out.push_back({"Hello-empty", {bare}});
    // A session as a client sees it, then as the master sees it: several messages back to back.
    out.push_back({"Welcome-session",
                   {test::sampleWelcome(), test::sampleTileAssign(), Heartbeat{},
                    test::sampleSceneUpdate(), test::sampleTileAssign(), Shutdown{}}});
    out.push_back({"Hello-session",
                   {test::sampleHello(), test::sampleSceneReady(), test::sampleTileResult(4),
                    Heartbeat{}, test::sampleError()}});
    return out;
}

void writeFile(const fs::path& path, const Bytes& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
    if (!out) throw std::runtime_error("cannot write " + path.string());
}

Bytes readFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot read " + path.string());
    return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// The uncompressed body of an encoded SceneData payload.
Bytes sceneDataBody(const Bytes& payload) {
    ByteReader in(payload, "SceneData");
    const std::uint64_t size = in.u64();
    return zstdDecompressExact(in.bytes(in.remaining()), size, "SceneData");
}

/// The planes of an encoded TileResult payload in the shape fuzz::parseTilePlanes reads.
Bytes tilePlanes(const Bytes& payload) {
    ByteReader in(payload, "TileResult");
    in.bytes(4 + 8 + 8 + 4 + 4 + 4 + 4);  // tile id and statistics
    const std::uint32_t count = in.u32(), planes = in.u32(), sent = in.u32();
    Bytes out{static_cast<std::uint8_t>(planes), static_cast<std::uint8_t>(sent)};
    for (std::uint32_t bit : {igi::kIrradiance, igi::kDepth, igi::kUnfiltered, igi::kGlossy}) {
        if (!(sent & bit)) continue;
        const auto reference = in.bytes(4);
        out.insert(out.end(), reference.begin(), reference.end());
    }
    const Bytes raw = zstdDecompressExact(in.blob(), std::size_t{bytesPerPixel(sent)} * count,
                                          "TileResult planes");
    out.insert(out.end(), raw.begin(), raw.end());
    return out;
}

void write(const fs::path& dir) {
    fs::create_directories(dir);
    for (const Seed& seed : seeds()) {
        Bytes stream;
        std::uint32_t frame = 3;
        for (const Message& m : seed.messages) {
            const Bytes bytes = encodeMessage(m, frame++, 1);
            stream.insert(stream.end(), bytes.begin(), bytes.end());
        }
        writeFile(dir / (seed.name + ".msg"), stream);
        if (seed.messages.size() != 1) continue;
        const Message& m = seed.messages.front();
        const Bytes payload = encodePayload(m);
        writeFile(dir / (seed.name + ".payload"), payload);
        if (typeOf(m) == MessageType::SceneData)
            writeFile(dir / (seed.name + ".body"), sceneDataBody(payload));
        if (typeOf(m) == MessageType::TileResult && std::get<TileResult>(m).channels.count > 0)
            writeFile(dir / (seed.name + ".body"), tilePlanes(payload));
    }
}

MessageType typeNamed(const std::string& name) {
    for (std::uint16_t t = 1; isKnownType(t); ++t) {
        if (messageTypeName(static_cast<MessageType>(t)) == name)
            return static_cast<MessageType>(t);
    }
    throw std::runtime_error("no message type is called '" + name + "'");
}

/// The payload fuzz_protocol makes of a .body seed.
Bytes wrapBody(MessageType type, const Bytes& body) {
    if (type == MessageType::SceneData) return fuzz::sceneDataPayloadFromBody(body);
    if (type == MessageType::TileResult) {
        if (auto payload = fuzz::tileResultPayloadFromPlanes(body)) return *payload;
        throw std::runtime_error("too short for a tile's planes");
    }
    throw std::runtime_error("only SceneData and TileResult have .body seeds");
}

/// Decodes a whole stream; throws when a message is refused or bytes are left over.
void checkStream(std::span<const std::uint8_t> bytes) {
    if (bytes.empty()) throw ProtocolError("empty stream");
    while (!bytes.empty()) {
        if (bytes.size() < kHeaderSize) throw ProtocolError("stream ends inside a header");
        const Header h = decodeHeader(bytes.first<kHeaderSize>());
        bytes = bytes.subspan(kHeaderSize);
        if (h.payloadSize > bytes.size()) throw ProtocolError("stream ends inside a payload");
        decodeMessage(h, bytes.first(h.payloadSize));
        bytes = bytes.subspan(h.payloadSize);
    }
}

int check(const fs::path& dir) {
    int checked = 0, failed = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
        const fs::path path = entry.path();
        const std::string stem = path.stem().string();
        const Bytes bytes = readFile(path);
        try {
            if (path.extension() == ".msg") {
                checkStream(bytes);
            } else if (path.extension() == ".payload" || path.extension() == ".body") {
                const MessageType type = typeNamed(stem.substr(0, stem.find('-')));
                const Bytes payload =
                    path.extension() == ".payload" ? bytes : wrapBody(type, bytes);
                Header h;
                h.type = type;
                h.payloadSize = static_cast<std::uint32_t>(payload.size());
                decodeMessage(h, payload);
            } else {
                throw std::runtime_error("unexpected file (not .msg, .payload or .body)");
            }
            ++checked;
        } catch (const std::exception& e) {
            std::fprintf(stderr, "%s: %s\n", path.string().c_str(), e.what());
            ++failed;
        }
    }
    std::printf("%d seeds decode, %d do not\n", checked, failed);
    if (failed > 0)
        std::fprintf(stderr,
                     "the build writes these seeds with the current encoder: a seed the decoder "
                     "refuses means they disagree, or make_protocol_seeds.cpp builds it wrong\n");
    return failed == 0 && checked > 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string mode = argc == 3 ? argv[1] : "";
    if (mode != "write" && mode != "check") {
        std::fprintf(stderr, "usage: %s write|check DIR\n", argv[0]);
        return 2;
    }
    try {
        if (mode == "check") return check(argv[2]);
        write(argv[2]);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
}
