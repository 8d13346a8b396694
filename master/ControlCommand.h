#pragma once

#include <string>
#include <vector>

#include "scene/Scene.h"
#include "scene/SceneChange.h"
#include "scene/SceneState.h"

namespace igi {

/// One command received on the master's control port (docs/ANIMATION.md, "Control commands").
struct ControlRequest {
    enum class Kind { Change, Status, Snapshot, Stop } kind = Kind::Status;
    std::vector<SceneChange> changes;  ///< for Change
    std::string path;                  ///< for Snapshot: where to write the image
};

/// The file name that control-command errors give (SceneError::file()).
inline constexpr const char* kControlCommandFile = "control command";

/// Parses one command line; `current` is the state the changes apply to (properties the
/// command does not give keep their current values). Throws SceneError (file "control
/// command") naming the JSON path.
ControlRequest parseControlCommand(const std::string& line, const Scene& scene,
                                   const SceneState& current);

}  // namespace igi
