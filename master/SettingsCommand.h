#pragma once

#include <string>
#include <vector>

#include "render/RenderSettings.h"
#include "scene/JsonReader.h"
#include "scene/SceneChange.h"

namespace igi {

/// The render settings a running session can change (the `settings` control command), as the
/// keys of a scene file's "render" section. The others are fixed for the session: the master's
/// tile layout, frame buffers, filter and accumulation are made from them when it starts.
std::vector<std::string> liveSettingKeys();

/// `{"cmd": "settings", <key>: <value>, ...}`: the settings in force (`current`) with the
/// command's keys applied, as one change. The keys, their values and ranges are the scene
/// file's "render" section's, checked by the same code; a key that is fixed for the session is
/// refused by name. Throws SceneError naming the key (and, for a value, its range); nothing is
/// changed then.
SettingsChange settingsChange(const JsonNode& command, const RenderSettings& current);

}  // namespace igi
