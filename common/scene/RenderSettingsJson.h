#pragma once

// Reads a scene file's "render" section into RenderSettings. Kept apart from the scene
// parser so that the master can apply the same keys (with the same checks and messages) from
// elsewhere, e.g. a settings file or a command-line JSON override.

#include <string>

#include <nlohmann/json_fwd.hpp>

#include "render/RenderSettings.h"

namespace igi {

/// Overwrites the members of `settings` named in `json` (an object; absent keys keep their
/// value). Throws SceneError naming `file` and `jsonPathPrefix` + "/key" for an unknown key, a
/// wrong type or a value out of range. Keys and ranges: docs/SCENE_FORMAT.md, "render".
void applyRenderSettingsJson(const nlohmann::json& json, RenderSettings& settings,
                             const std::string& file, const std::string& jsonPathPrefix);

/// Every setting as a "render" section that applyRenderSettingsJson reads back to the same
/// settings: what a run's statistics record of how it rendered.
nlohmann::json renderSettingsJson(const RenderSettings& settings);

}  // namespace igi
