#include "SettingsCommand.h"

#include <nlohmann/json.hpp>

#include "scene/RenderSettingsJson.h"

namespace igi {
namespace {

using Settings = const RenderSettings&;

struct SettingCompare {
    const char* key;
    bool (*same)(const RenderSettings&, const RenderSettings&);
};

// The settings the master's frames are made from: the tile layout, the frame buffers, the
// discontinuity buffer and the accumulation. They change live: the master lets the frames in
// flight finish and rebuilds these at the change (Master::framesFollowSettings).
const std::vector<SettingCompare>& frameSettings() {
    static const std::vector<SettingCompare> frame = {
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
    };
    return frame;
}

// Fixed for the session. tile_size bounds the size of a tile result, which every client
// connection is given as a limit when it is accepted (a hostile client cannot make the master
// read more); the seed is every client's since the handshake. (The GI mode and the integrator
// are the clients' alone; the joiners' history follows them, SceneTimeline.)
const std::vector<SettingCompare>& fixedSettings() {
    static const std::vector<SettingCompare> fixed = {
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
           (key == std::string("seed")
                ? "' is fixed while the session runs (every client has drawn from it since it "
                  "joined)"
                : "' is fixed while the session runs (it bounds the size of the tile results "
                  "every client connection accepts)") +
           "; these change live: " + liveList();
}

}  // namespace

bool sameFrameSettings(const RenderSettings& a, const RenderSettings& b) {
    for (const SettingCompare& f : frameSettings())
        if (!f.same(a, b)) return false;
    return true;
}

std::vector<std::string> liveSettingKeys() {
    std::vector<std::string> keys;
    const nlohmann::json every = renderSettingsJson(RenderSettings{});  // outlives the loop
    for (const auto& [key, value] : every.items()) {
        bool fixed = false;
        for (const SettingCompare& f : fixedSettings()) fixed = fixed || key == f.key;
        if (!fixed) keys.push_back(key);
    }
    keys.push_back("converge");      // sets the estimator's parts at once
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
    for (const SettingCompare& f : fixedSettings()) {
        if (f.same(current, next)) continue;
        JsonNode(command.value(), command.file(), command.path() + "/" + f.key)
            .fail(fixedReason(f.key));
    }
    request.change = SettingsChange{next};
    return request;
}

}  // namespace igi
