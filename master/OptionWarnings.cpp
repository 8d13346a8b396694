#include "OptionWarnings.h"

#include <nlohmann/json.hpp>

#include "RenderFlags.h"

namespace igi {
namespace {

// The mode a key of the render section belongs to, by its prefix; igi: every mode's.
bool keyServesMode(const std::string& key, GiMode mode) {
    auto starts = [&](const char* prefix) { return key.rfind(prefix, 0) == 0; };
    if (starts("stream_")) return mode == GiMode::Stream;
    if (starts("spt_")) return mode == GiMode::Spt;
    if (starts("cache_")) return mode == GiMode::Cache || mode == GiMode::PhotonMap;
    if (starts("photonmap_")) return mode == GiMode::PhotonMap;
    // The other modes' first frames keep what their method keeps (RenderSettings).
    if (key == "first_frame_divisor") return mode == GiMode::Igi;
    return true;
}

void warnSequence(const MasterOptions& o, std::vector<std::string>& out) {
    if (o.sequenceFrames.empty()) return;
    if (o.outputSequence.empty()) {
        out.push_back("--sequence-frames does nothing without --output-sequence");
        return;
    }
    if (o.frames == 0) return;
    std::string past;
    for (std::uint32_t f : o.sequenceFrames)
        if (f >= std::uint32_t(o.frames)) past += (past.empty() ? "" : ", ") + std::to_string(f);
    if (!past.empty())
        out.push_back("--sequence-frames " + past + ": past the last frame (--frames " +
                      std::to_string(o.frames) + " renders frames 0 to " +
                      std::to_string(o.frames - 1) + "), never written");
}

void warnSettings(const nlohmann::json& overrides, const RenderSettings& s,
                  std::vector<std::string>& out) {
    const bool path = s.integrator == IntegratorKind::Path;
    if (!path && overrides.contains("path_samples"))
        out.push_back("--spp sets the path tracer's samples; IGI ignores it (--integrator path)");
    if (path && overrides.contains("gi") && s.gi != GiMode::Igi)
        out.push_back(std::string("--gi ") + giModeName(s.gi) +
                      " does nothing with --integrator path (the path tracer has no GI mode)");
    if (path) return;
    for (const auto& [key, value] : overrides.items())
        if (!keyServesMode(key, s.gi))
            out.push_back(flagForRenderKey(key) + " does nothing with --gi " + giModeName(s.gi));
}

}  // namespace

std::vector<std::string> uselessOptionWarnings(const MasterOptions& options,
                                               const nlohmann::json& overrides,
                                               const RenderSettings& settings) {
    std::vector<std::string> out;
    warnSequence(options, out);
    warnSettings(overrides, settings, out);
    if (options.frames > 0 && options.outputs.empty() && options.outputSequence.empty())
        out.push_back(
            "no --output (nor --output-sequence): the image of this run is written "
            "nowhere");
    return out;
}

}  // namespace igi
