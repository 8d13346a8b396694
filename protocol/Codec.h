#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "Messages.h"
#include "ProtocolError.h"
#include "TileCodes.h"

namespace igi::proto {

/// Largest payload accepted for each type (docs/PROTOCOL.md, "Limits"). A header announcing
/// more is refused before anything is allocated for its payload.
constexpr std::uint32_t kSmallPayloadLimit = 4u << 10;
constexpr std::uint32_t kErrorPayloadLimit = 64u << 10;
constexpr std::uint32_t kTileResultPayloadLimit = 64u << 20;
constexpr std::uint32_t kSceneDataPayloadLimit = 1u << 30;
constexpr std::uint32_t kSceneUpdatePayloadLimit = 16u << 20;
/// Largest uncompressed SceneData body a client will allocate.
constexpr std::uint64_t kSceneDataBodyLimit = std::uint64_t{2} << 30;

std::uint32_t maxPayloadSize(MessageType type);
bool isKnownType(std::uint16_t type);
/// "Hello", "TileResult", ... ("type 77" for an unknown one).
std::string messageTypeName(MessageType type);
MessageType typeOf(const Message& message);

std::array<std::uint8_t, kHeaderSize> encodeHeader(const Header& header);
/// Decodes and validates a header: magic, version, known type, reserved word zero and the
/// payload size within the type's limit. Throws ProtocolError naming what is wrong.
Header decodeHeader(std::span<const std::uint8_t, kHeaderSize> bytes);

/// The payload alone; throws ProtocolError if it exceeds its type's limit.
std::vector<std::uint8_t> encodePayload(const Message& message);
/// Header and payload, ready for the socket.
std::vector<std::uint8_t> encodeMessage(const Message& message, std::uint32_t frame,
                                        std::uint32_t epoch);
/// Rewrites the frame and epoch of an encoded message in place (a recorded result sent again).
void setHeaderFrameAndEpoch(std::vector<std::uint8_t>& message, std::uint32_t frame,
                            std::uint32_t epoch);

/// The tile a TileResult payload is for (its first field), without decoding the rest: lets the
/// master drop a duplicate before spending time on it. Throws ProtocolError if too short.
std::uint32_t peekTileId(std::span<const std::uint8_t> payload);

/// Decodes and validates the payload of a (decoded) header. Throws ProtocolError when the
/// payload is truncated, has trailing bytes, or holds an invalid enum, count, index or range.
Message decodeMessage(const Header& header, std::span<const std::uint8_t> payload);

/// A TileResult decoded only as far as its compressed codes: what the master decompresses
/// straight into its frame (CodedFrame.h). `codes` points into the payload.
struct TileResultCodes {
    std::uint32_t tileId = 0;
    TileStats stats;
    TileCodes codes;
};
/// decodeMessage for a TileResult, stopping at the compressed codes: the same checks (the
/// zstd frame's are made when it is decompressed).
TileResultCodes decodeTileResultCodes(const Header& header, std::span<const std::uint8_t> payload);

}  // namespace igi::proto
