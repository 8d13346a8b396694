#pragma once

#include "ByteReader.h"
#include "ByteWriter.h"
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

void writeSceneBundle(ByteWriter& out, const SceneBundle& b);
SceneBundle readSceneBundle(ByteReader& in);

}  // namespace igi::proto
