#include "SettingsCommand.h"

#include <nlohmann/json.hpp>

#include "scene/RenderSettingsJson.h"

namespace igi {
namespace {

using Settings = const RenderSettings&;

// A setting the master itself works with: changing it would take a new tile layout, frame
// buffers, filter or accumulation, which a running session does not rebuild. (The GI mode and
// the integrator are the clients' alone; the joiners' history follows them, SceneTimeline.)
struct FixedSetting {
    const char* key;
    bool (*same)(const RenderSettings&, const RenderSettings&);
};

const std::vector<FixedSetting>& fixedSettings() {
    static const std::vector<FixedSetting> fixed = {
        {"interleave",
         [](Settings a, Settings b) {
             return a.interleaveX == b.interleaveX && a.interleaveY == b.interleaveY;
         }},
        {"filter",
         [](Settings a, Settings b) { return a.filterX == b.filterX && a.filterY == b.filterY; }},
        {"filter_depth_threshold",
         [](Settings a, Settings b) { return a.filterDepthThreshold == b.filterDepthThreshold; }},
        {"filter_normal_threshold",
         [](Settings a, Settings b) { return a.filterNormalThreshold == b.filterNormalThreshold; }},
        {"progressive_filter",
         [](Settings a, Settings b) { return a.progressiveFilter == b.progressiveFilter; }},
        {"accumulate", [](Settings a, Settings b) { return a.accumulate == b.accumulate; }},
        {"tile_size", [](Settings a, Settings b) { return a.tileSize == b.tileSize; }},
        {"seed", [](Settings a, Settings b) { return a.seed == b.seed; }},
    };
    return fixed;
}

std::string liveList() {
    std::string list;
    for (const std::string& k : liveSettingKeys()) list += (list.empty() ? "" : ", ") + k;
    return list;
}

std::string fixedReason(const char* key) {
    return std::string("'") + key +
           "' is fixed while the session runs (the master makes its tiles, filter and "
           "accumulation from it when it starts); these change live: " +
           liveList();
}

}  // namespace

std::vector<std::string> liveSettingKeys() {
    std::vector<std::string> keys;
    const nlohmann::json every = renderSettingsJson(RenderSettings{});  // outlives the loop
    for (const auto& [key, value] : every.items()) {
        bool fixed = false;
        for (const FixedSetting& f : fixedSettings()) fixed = fixed || key == f.key;
        if (!fixed) keys.push_back(key);
    }
    keys.push_back("converge");      // sets the estimator's parts at once (not progressive_filter)
    keys.push_back("target_error");  // the master's, not a render setting (--target-error)
    return keys;
}

SettingsRequest settingsRequest(const JsonNode& command, const RenderSettings& current) {
    command.requireObject();
    nlohmann::json keys = command.value();
    keys.erase("cmd");
    if (keys.empty()) command.fail("the command changes nothing (give one of: " + liveList() + ")");
    SettingsRequest request;
    if (auto target = command.find("target_error")) {
        request.targetError = target->number(NumberRange::closed(0, kMaxTargetError));
        keys.erase("target_error");
        if (keys.empty()) return request;
    }
    RenderSettings next = current;
    // The scene file's reader: the same keys, checks and messages (naming the key and range).
    applyRenderSettingsJson(keys, next, command.file(), command.path());
    for (const FixedSetting& f : fixedSettings()) {
        if (f.same(current, next)) continue;
        // "converge" changes progressive_filter without naming it: say which key did.
        const std::string given = keys.contains(f.key) ? f.key : "converge";
        JsonNode(command.value(), command.file(), command.path() + "/" + given)
            .fail(fixedReason(f.key));
    }
    request.change = SettingsChange{next};
    return request;
}

}  // namespace igi
