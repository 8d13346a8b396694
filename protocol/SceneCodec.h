#pragma once

#include "ByteReader.h"
#include "ByteWriter.h"
#include "Messages.h"
#include "render/RenderSettings.h"
#include "scene/Camera.h"
#include "scene/Scene.h"
#include "scene/SceneLoader.h"

namespace igi::proto {

// The pieces of a SceneData body, each field in a fixed order (docs/PROTOCOL.md). The readers
// validate every enum and range, so a client never renders with settings a master would refuse.

void writeRenderSettings(ByteWriter& out, const RenderSettings& s);
RenderSettings readRenderSettings(ByteReader& in);

void writeImageSettings(ByteWriter& out, const ImageSettings& s);
ImageSettings readImageSettings(ByteReader& in);

void writeCamera(ByteWriter& out, const Camera& c);
Camera readCamera(ByteReader& in);

/// SceneData's base frame and history: u32 baseFirstFrame, u32 count <= kMaxHistoryEpochs,
/// then per epoch u32 firstFrame and its changes (ChangeCodec).
void writeSceneHistory(ByteWriter& out, std::uint32_t baseFirstFrame,
                       const std::vector<EpochChanges>& history);
std::vector<EpochChanges> readSceneHistory(ByteReader& in, std::uint32_t& baseFirstFrame);

void writeSceneBundle(ByteWriter& out, const SceneBundle& b);
SceneBundle readSceneBundle(ByteReader& in);

}  // namespace igi::proto
