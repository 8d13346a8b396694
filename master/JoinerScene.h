#pragma once

#include "Messages.h"
#include "SceneTimeline.h"
#include "TileScheduler.h"

namespace igi {

/// Makes `data` (the scene as loaded, with its files) what client `client`, joining now, is
/// sent: the changes that bring the loaded scene to the timeline's base epoch, and the epochs
/// since, which a GI mode with lighting across epochs replays. Warns when that history no
/// longer reaches back to where the lighting started: the joiner's lighting then differs.
void prepareJoinerScene(proto::SceneData& data, const SceneTimeline& timeline, ClientId client);

}  // namespace igi
