#pragma once

#include <string>
#include <vector>

namespace igi {

/// The values `--log-level` takes (spdlog's names; any case on the command line). An unknown
/// name must be refused: spdlog reads it as "off", which silenced errors too.
inline const std::vector<std::string>& logLevelNames() {
    static const std::vector<std::string> names = {"trace",   "debug", "info",     "warn",
                                                   "warning", "error", "critical", "off"};
    return names;
}

}  // namespace igi
