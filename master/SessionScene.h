#pragma once

#include <nlohmann/json.hpp>

#include "MasterOptions.h"
#include "scene/Scene.h"
#include "scene/SceneLoader.h"

namespace igi {

/// The scene this session renders: the scene file as loaded (its files into `bundle`, for the
/// clients), with the command line's render settings, image size and exposure over it. Warns
/// about options that do nothing and says how the scene is lit. Throws SceneError for the file
/// and std::invalid_argument, naming the flag, for a bad command-line setting.
Scene loadSessionScene(const MasterOptions& options, SceneBundle& bundle);

/// Every setting that shaped the run, for the statistics file: two runs' statistics can be told
/// apart.
nlohmann::json sessionJson(const MasterOptions& options, const Scene& scene);

class Animation;
/// The frames a session with `animation` renders: without --frames, the animation to its last
/// keyframe; with it, --frames, warned about when it stops before the last keyframe.
int framesWithAnimation(const MasterOptions& options, const Animation& animation);

}  // namespace igi
