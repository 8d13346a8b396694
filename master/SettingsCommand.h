#pragma once

#include <optional>
#include <string>
#include <vector>

#include "render/RenderSettings.h"
#include "scene/JsonReader.h"
#include "scene/SceneChange.h"

namespace igi {

/// The render settings a running session can change (the `settings` control command), as the
/// keys of a scene file's "render" section, and `target_error`. The others (tile_size, seed)
/// are fixed for the session.
std::vector<std::string> liveSettingKeys();

/// Whether the master's frames are made the same way under `a` and `b`: the same tile layout,
/// frame buffers, discontinuity buffer and accumulation (interleave, filter, its thresholds,
/// progressive_filter, accumulate). When not, the master rebuilds them at the change.
bool sameFrameSettings(const RenderSettings& a, const RenderSettings& b);

/// The most a target error may be (a relMSE; 0: no target).
inline constexpr double kMaxTargetError = 100;

/// What a settings command asks: new render settings (a new epoch), a new target error
/// (--target-error's, 0: none; not a scene change), or both.
struct SettingsRequest {
    std::optional<SettingsChange> change;
    std::optional<double> targetError;
};

/// `{"cmd": "settings", <key>: <value>, ...}`: the settings in force (`current`) with the
/// command's keys applied, as one change, and `target_error`. The keys, their values and ranges
/// are the scene file's "render" section's, checked by the same code; a key that is fixed for
/// the session is refused by name. Throws SceneError naming the key (and, for a value, its
/// range); nothing is changed then.
SettingsRequest settingsRequest(const JsonNode& command, const RenderSettings& current);

}  // namespace igi
