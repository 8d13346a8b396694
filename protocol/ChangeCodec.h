#pragma once

#include <cstdint>
#include <vector>

#include "ByteReader.h"
#include "ByteWriter.h"
#include "scene/SceneChange.h"

namespace igi::proto {

/// Most changes one SceneUpdate (or one SceneData) may carry. A decoder checks the count
/// against it, and against the bytes that remain, before reserving anything for the changes.
constexpr std::uint32_t kMaxSceneChanges = 1'000'000;

/// Fewest bytes a change takes on the wire (the environment: tag, a vec3, a float).
constexpr std::size_t kMinChangeBytes = 1 + 12 + 4;

/// Wire tags of the change kinds (docs/PROTOCOL.md, "Scene changes").
enum class ChangeTag : std::uint8_t {
    Camera = 0,
    Transform = 1,
    PunctualLight = 2,
    QuadLight = 3,
    Material = 4,
    Environment = 5,
    Settings = 6,
};

/// One change: a u8 tag, then its fields. Names and the material's texture are not sent: a
/// change never alters them.
void writeSceneChange(ByteWriter& out, const SceneChange& change);
/// Reads and validates change number `index` (the number appears in every error): a known
/// tag, finite floats, booleans 0 or 1, a known reflection kind, a usable camera, non-zero
/// scales, ior > 0, phongExponent >= 0, colours >= 0 (an environment's radiance too). Indices are
/// not checked here: the protocol does not know the scene (applyChanges does).
SceneChange readSceneChange(ByteReader& in, std::uint32_t index);

/// A u32 count, then the changes in order. Throws ProtocolError beyond kMaxSceneChanges.
void writeSceneChanges(ByteWriter& out, const std::vector<SceneChange>& changes);
std::vector<SceneChange> readSceneChanges(ByteReader& in);

}  // namespace igi::proto
