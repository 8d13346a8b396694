// libFuzzer target: the wire decoder (protocol/Codec.h) on bytes from a hostile peer.
//
// Every input is used four ways:
//  1. as a connection's byte stream, read the way the master and the clients read it: a
//     24-byte header, then the payload it announces, then the next header, ... until the bytes
//     run out, a message is incomplete or one is refused (where a peer closes the connection);
//  2. as the payload of a message of every type whose limit allows its size, so that each
//     decoder is reached without the fuzzer having to discover a valid header first;
//  3. as the uncompressed body of a SceneData and 4. as the planes of a TileResult, compressed
//     into a well-formed payload (CompressedParts.h): mutated zstd frames are nearly always
//     corrupt, and the decoders behind them would see little but the seeds.
// ProtocolError is the expected answer to bad bytes. Anything else is a bug: another exception
// type, a sanitizer report, an allocation beyond libFuzzer's -malloc_limit_mb, a timeout, or a
// decoded message that does not encode back (see checkReencodes).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <span>
#include <typeinfo>
#include <vector>

#include "Codec.h"
#include "CodedFrame.h"
#include "CompressedParts.h"

namespace {

using namespace igi::proto;

using Bytes = std::span<const std::uint8_t>;

[[noreturn]] void bug(const char* what, MessageType type) {
    std::fprintf(stderr, "fuzz_protocol: %s (%s)\n", what, messageTypeName(type).c_str());
    std::abort();
}

Message decodePayload(MessageType type, Bytes payload) {
    Header h;
    h.type = type;
    h.payloadSize = static_cast<std::uint32_t>(payload.size());
    return decodeMessage(h, payload);
}

/// Whatever the decoder accepts, the encoder must be able to write back: a value one side
/// lets through and the other refuses (or reads differently) means the two disagree about the
/// format. Messages without compression or quantization re-encode to exactly the bytes
/// received (the encoding is canonical); SceneData (recompressed) and TileResult (requantized)
/// must decode again, and SceneData must then encode the same again.
void checkReencodes(const Message& message, Bytes received) {
    const MessageType type = typeOf(message);
    std::vector<std::uint8_t> again;
    try {
        again = encodePayload(message);
        const Message decodedAgain = decodePayload(type, again);
        if (type == MessageType::SceneData && encodePayload(decodedAgain) != again)
            bug("SceneData does not encode the same after a round trip", type);
        if (type == MessageType::TileResult && std::get<TileResult>(decodedAgain).channels.count !=
                                                   std::get<TileResult>(message).channels.count)
            bug("TileResult changes its pixel count in a round trip", type);
    } catch (const ProtocolError& e) {
        std::fprintf(stderr, "fuzz_protocol: %s\n", e.what());
        bug("a decoded message does not encode and decode again", type);
    }
    const bool canonical = type != MessageType::SceneData && type != MessageType::TileResult;
    if (canonical && !std::equal(again.begin(), again.end(), received.begin(), received.end()))
        bug("a decoded message encodes to other bytes than were received", type);
}

/// The master decodes a TileResult its own way, as far as the codes, which it decompresses
/// into its frame and dequantizes row by row (CodedFrame.h): it must refuse exactly what
/// decodeMessage refuses, and read what it accepts without a sanitizer report.
void checkMasterTilePath(const Header& header, Bytes payload, bool accepted) {
    if (header.type != MessageType::TileResult) return;
    bool refused = false;
    try {
        const TileResultCodes result = decodeTileResultCodes(header, payload);
        const std::uint32_t count = result.codes.count;
        if (count == 0 || count > 4096) return;  // a one-row frame of the tile's pixels
        const igi::Tile tile{0, 0, int(count), 1, 0, 0};
        CodedFrame frame;
        frame.reuse(int(count), 1, 1, 1, int(count));
        frame.scatter(tile, result.codes);
        igi::FrameRow row;
        frame.decodeRow(0, row);
    } catch (const ProtocolError&) {
        refused = true;
    }
    if (refused == accepted)
        bug("the master's tile decoder and decodeMessage disagree", header.type);
}

/// Decodes `payload` as a message of the header's type; false when it is refused.
bool tryDecode(const Header& header, Bytes payload) {
    Message message;
    try {
        message = decodeMessage(header, payload);
    } catch (const ProtocolError&) {
        checkMasterTilePath(header, payload, false);
        return false;
    }
    checkMasterTilePath(header, payload, true);
    checkReencodes(message, payload);
    return true;
}

void decodeStream(Bytes bytes) {
    while (bytes.size() >= kHeaderSize) {
        Header header;
        try {
            header = decodeHeader(bytes.first<kHeaderSize>());
        } catch (const ProtocolError&) {
            return;
        }
        bytes = bytes.subspan(kHeaderSize);
        if (header.payloadSize > bytes.size()) return;  // the reader would wait for more
        const Bytes payload = bytes.first(header.payloadSize);
        if (header.type == MessageType::TileResult) {
            try {
                (void)peekTileId(payload);  // the master looks at the tile id first
            } catch (const ProtocolError&) {
                return;
            }
        }
        if (!tryDecode(header, payload)) return;
        bytes = bytes.subspan(header.payloadSize);
    }
}

void decodeAsEveryType(Bytes payload) {
    for (std::uint16_t t = 1; isKnownType(t); ++t) {
        const auto type = static_cast<MessageType>(t);
        if (payload.size() > maxPayloadSize(type)) continue;  // decodeHeader refuses these
        Header header;
        header.type = type;
        header.payloadSize = static_cast<std::uint32_t>(payload.size());
        tryDecode(header, payload);
    }
}

void decodeCompressedParts(Bytes input) {
    Header header;
    const std::vector<std::uint8_t> scene = fuzz::sceneDataPayloadFromBody(input);
    if (scene.size() <= maxPayloadSize(MessageType::SceneData)) {
        header.type = MessageType::SceneData;
        header.payloadSize = static_cast<std::uint32_t>(scene.size());
        tryDecode(header, scene);
    }
    if (const auto tile = fuzz::tileResultPayloadFromPlanes(input)) {
        header.type = MessageType::TileResult;
        header.payloadSize = static_cast<std::uint32_t>(tile->size());
        tryDecode(header, *tile);
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const Bytes input(data, size);
    try {
        decodeStream(input);
        decodeAsEveryType(input);
        decodeCompressedParts(input);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fuzz_protocol: unexpected %s: %s\n", typeid(e).name(), e.what());
        std::abort();
    }
    return 0;
}
