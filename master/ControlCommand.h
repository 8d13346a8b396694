#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scene/Scene.h"
#include "scene/SceneChange.h"
#include "scene/SceneState.h"

namespace igi {

/// One command received on the master's control port (docs/ANIMATION.md, "Control commands").
struct ControlRequest {
    /// Change: moves the scene, or changes its render settings (a new epoch). Status, Scene and
    /// Pick only ask: the session's progress; the scene's objects, lights and camera; what is under
    /// an image position. Exposure sets the display exposure of the view and of PNG images written
    /// from then on (not a scene change: accumulation goes on).
    enum class Kind { Change, Status, Scene, Pick, Exposure, Snapshot, Stop } kind = Kind::Status;
    std::vector<SceneChange> changes;  ///< for Change
    /// For Change (a settings command): a new target error, the master's (0: none).
    std::optional<double> targetError;
    /// For Snapshot: where to write the image; empty: the master picks a new .exr name beside
    /// its outputs (what the web view's save button asks for).
    std::string path;
    float x = 0, y = 0;  ///< for Pick: the image position, pixels from the top-left corner
    float exposure = 0;  ///< for Exposure: stops
    /// What the command changed beyond what it said (a material scaled down), for the reply:
    /// the one who sent it may not see the master's log.
    std::vector<std::string> warnings;
};

/// Exposures a command may set, in stops (beyond them an image is all black or all white).
inline constexpr double kMaxExposureStops = 20;

/// The file name that control-command errors give (SceneError::file()).
inline constexpr const char* kControlCommandFile = "control command";

/// Parses one command line; `current` is the state the changes apply to (properties the
/// command does not give keep their current values). Throws SceneError (file "control
/// command") naming the JSON path.
ControlRequest parseControlCommand(const std::string& line, const Scene& scene,
                                   const SceneState& current);

}  // namespace igi
