#pragma once

#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "MasterOptions.h"
#include "render/RenderSettings.h"

namespace igi {

/// Warnings for options that would do nothing in this run: --sequence-frames without
/// --output-sequence or past --frames, --spp with IGI, a GI mode or a mode's settings with
/// the path tracer or another mode, and a finite run that writes no image. A user who gave an
/// option meant something by it; a silent no-op hides the mistake. `overrides` are the
/// render settings given on the command line (MasterOptions::renderOverridesJson), `settings`
/// the run's, after the scene file's.
std::vector<std::string> uselessOptionWarnings(const MasterOptions& options,
                                               const nlohmann::json& overrides,
                                               const RenderSettings& settings);

}  // namespace igi
