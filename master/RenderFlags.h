#pragma once

#include <string>

namespace igi {

class SceneError;

/// The igi-master flag that sets a key of the scene file's "render" section: "--" and the key
/// with dashes ("direct_samples" -> "--direct-samples"), but for the few whose flag says it
/// otherwise ("path_samples" -> "--spp", "accumulate" -> "--no-accumulate").
std::string flagForRenderKey(const std::string& key);

/// A render setting from the command line, refused by the scene file's checks: the message
/// names the flag the user typed, not the scene file's key ("--spp: must be in [1, 65536], got
/// 0", not "command line: /render/path_samples: ..."). `error` names a path under "/render".
std::string commandLineMessage(const SceneError& error);

}  // namespace igi
