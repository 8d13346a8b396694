#include "SessionControl.h"

#include <spdlog/spdlog.h>

#include "ControlCommand.h"
#include "OpenPort.h"
#include "ScenePick.h"
#include "SettingsCommand.h"
#include "scene/RenderSettingsJson.h"

namespace igi {
namespace {

nlohmann::json vec3Json(glm::vec3 v) {
    return nlohmann::json::array({v.x, v.y, v.z});
}

nlohmann::json cameraJson(const Camera& c) {
    return {{"position", vec3Json(c.position)},
            {"look_at", vec3Json(c.lookAt)},
            {"up", vec3Json(c.up)},
            {"fov_y", c.fovYDeg}};
}

// What a user reads to know which estimator runs: the mode and the settings that set its cost.
nlohmann::json settingsJson(const RenderSettings& s) {
    if (s.integrator == IntegratorKind::Path)
        return {{"integrator", "path"},
                {"samples_per_pixel", s.pathSamples},
                {"max_path_length", s.maxPathLength}};
    nlohmann::json j{{"integrator", "igi"},
                     {"gi", giModeName(s.gi)},
                     {"interleave", fmt::format("{}x{}", s.interleaveX, s.interleaveY)},
                     {"direct_samples", s.directSamples},
                     {"caustic_photons", s.causticPhotons},
                     {"accumulate", s.accumulate},
                     {"roulette", s.roulette}};
    if (s.gi == GiMode::Igi) j["indirect_vpls"] = s.indirectVpls;
    if (s.gi == GiMode::Spt) j["spt_groups"] = s.sptGroups, j["spt_budget"] = s.sptBudget;
    if (s.gi == GiMode::Stream)
        j["stream_vsls"] = s.streamVsls, j["stream_window"] = s.streamWindow;
    if (s.gi == GiMode::Cache)
        j["cache_spacing"] = s.cacheSpacing, j["cache_radius"] = s.cacheRadius;
    if (s.gi == GiMode::PhotonMap)
        j["photonmap_photons"] = s.photonmapGroups * s.photonmapPhotons,
        j["photonmap_caustics"] = s.photonmapScreenCaustics ? "screen" : "grid";
    return j;
}

}  // namespace

SessionControl::SessionControl(Frames& frames, const MasterOptions& options, Scene& scene,
                               SceneTimeline& timeline, Statistics& stats,
                               const ClientRoster& roster, const FrameCompositor& compositor,
                               FrameOutputs& outputs, std::chrono::steady_clock::time_point created)
    : frames_(frames),
      options_(options),
      scene_(scene),
      timeline_(timeline),
      stats_(stats),
      roster_(roster),
      compositor_(compositor),
      outputs_(outputs),
      created_(created) {}

void SessionControl::openPorts(boost::asio::io_context& io) {
    if (options_.control) {
        control_ = openPort("--control", options_.controlHost, options_.controlPort, [&] {
            return std::make_unique<ControlServer>(
                io, options_.controlHost, options_.controlPort,
                [this](const std::string& line, ControlServer::Reply reply) {
                    handle(line, std::move(reply), "igi-ctl");
                });
        });
        spdlog::info("control commands on {}:{}", options_.controlHost, control_->port());
    }
    if (options_.view)
        outputs_.startView([this](const std::string& line, ControlServer::Reply reply) {
            handle(line, std::move(reply), "view");
        });
}

void SessionControl::closePorts() {
    if (control_) control_->close();
}

void SessionControl::handle(const std::string& line, ControlServer::Reply reply, const char* from) {
    auto error = [&](const std::string& what) {
        spdlog::log(std::string(from) == "view" ? spdlog::level::debug : spdlog::level::warn,
                    "{} command refused: {}", from, what);
        reply(nlohmann::json{{"ok", false}, {"error", what}}.dump());
    };
    ControlRequest request;
    try {
        request = parseControlCommand(line, scene_, timeline_.controlled());
    } catch (const std::exception& e) {
        return error(e.what());
    }
    // What changed a session, and when, belongs in its log; the queries that scripts and the
    // view repeat do not.
    const bool query = request.kind == ControlRequest::Kind::Status ||
                       request.kind == ControlRequest::Kind::Scene ||
                       request.kind == ControlRequest::Kind::Pick;
    spdlog::log(query || std::string(from) == "view" ? spdlog::level::debug : spdlog::level::info,
                "{} command at frame {}: {}", from, frames_.nextFrame(), line);
    switch (request.kind) {
        case ControlRequest::Kind::Change:
            try {
                timeline_.control(request.changes);
            } catch (const std::exception& e) {
                return error(e.what());
            }
            if (request.targetError) frames_.setTargetError(*request.targetError);
            frames_.resume(!request.changes.empty());
            {
                nlohmann::json answer{{"ok", true},
                                      {"changes", request.changes.size()},
                                      {"from_frame", frames_.nextFrame()}};
                // The settings now in force, as a scene file's "render" section would say.
                if (changesSettings(request.changes))
                    answer["settings"] = renderSettingsJson(timeline_.controlled().render);
                if (request.targetError) answer["target_error"] = *request.targetError;
                if (!request.warnings.empty()) answer["warnings"] = request.warnings;
                return reply(answer.dump());
            }
        case ControlRequest::Kind::Status: {
            nlohmann::json status = statusJson();
            status["ok"] = true;
            return reply(status.dump());
        }
        case ControlRequest::Kind::Scene: {
            nlohmann::json scene = sceneJson();
            scene["ok"] = true;
            return reply(scene.dump());
        }
        case ControlRequest::Kind::Pick:
            return reply(pickJson(request.x, request.y).dump());
        case ControlRequest::Kind::Exposure:
            // Display only: the frames, their accumulation and the EXR outputs do not change.
            scene_.image.exposure = request.exposure;
            return reply(nlohmann::json{{"ok", true}, {"exposure", request.exposure}}.dump());
        case ControlRequest::Kind::Snapshot:
            return outputs_.snapshot(request.path, std::move(reply), frames_.nextFrame());
        case ControlRequest::Kind::Stop:
            reply(nlohmann::json{{"ok", true}, {"frames_done", frames_.framesDone()}}.dump());
            return frames_.stop();
    }
}

nlohmann::json SessionControl::statusJson() {
    const Statistics::Rates& rates = stats_.sampleRates(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - created_).count());
    nlohmann::json clients = nlohmann::json::array();
    for (const auto& [id, s] : roster_.clients()) {
        if (!s.ready) continue;
        const auto rays = rates.raysPerSecond.find(id);
        const auto tiles = rates.tilesPerSecond.find(id);
        clients.push_back(
            {{"id", id},
             {"host", s.host},
             {"address", s.connection->peer()},
             {"threads", s.threads},
             {"tiles_per_s", tiles == rates.tilesPerSecond.end() ? 0.0 : tiles->second},
             {"mrays_per_s", rays == rates.raysPerSecond.end() ? 0.0 : rays->second * 1e-6}});
    }
    nlohmann::json status = {{"frames_done", frames_.framesDone()},
                             {"frames_total", options_.frames},
                             {"epoch", timeline_.epoch()},
                             {"accumulated", compositor_.accumulatedFrames()},
                             {"clients", roster_.readyCount()},
                             {"client_list", clients},
                             {"fps", stats_.recentFps()},
                             {"wire_mb_per_s", rates.wireBytesPerSecond * 1e-6},
                             {"camera", cameraJson(timeline_.controlled().camera)},
                             {"exposure", scene_.image.exposure},
                             {"width", scene_.image.width},
                             {"height", scene_.image.height},
                             {"settings", settingsJson(timeline_.controlled().render)}};
    status.update(frames_.errorJson());
    return status;
}

nlohmann::json SessionControl::sceneJson() const {
    const SceneState& state = timeline_.controlled();
    nlohmann::json objects = nlohmann::json::array();
    for (std::size_t m = 0; m < scene_.meshes.size(); ++m) {
        if (scene_.meshes[m].partOf >= 0) continue;  // an instance: its object moves it
        const Transform& t = state.transforms[m];
        objects.push_back({{"name", scene_.meshes[m].name},
                           {"translate", vec3Json(t.translate)},
                           {"rotate_deg", vec3Json(t.rotateDeg)},
                           {"scale", vec3Json(t.scale)}});
    }
    nlohmann::json lights = nlohmann::json::array();
    for (const QuadLight& l : state.quadLights)
        lights.push_back(
            {{"name", l.name}, {"type", "quad"}, {"on", l.on}, {"radiance", vec3Json(l.radiance)}});
    for (const PunctualLight& l : state.punctualLights) {
        const bool sun = l.kind == LightKind::Directional;
        nlohmann::json light = {{"name", l.name},
                                {"type", l.kind == LightKind::Point ? "point"
                                         : sun                      ? "directional"
                                                                    : "spot"},
                                {"on", l.on},
                                {sun ? "irradiance" : "intensity", vec3Json(l.intensity)}};
        if (l.kind != LightKind::Point) light["direction"] = vec3Json(l.direction);
        lights.push_back(std::move(light));
    }
    // The sky as the environment command sets it (the web view's sky sliders start from it).
    const nlohmann::json environment = {{"radiance", vec3Json(state.environment.radiance)},
                                        {"rotate_deg", state.environment.rotateDeg},
                                        {"map", state.environment.texture >= 0}};
    return {{"objects", objects},
            {"lights", lights},
            {"environment", environment},
            // The render settings in force and those a settings command may change (the web
            // view's settings panel).
            {"settings", renderSettingsJson(state.render)},
            {"live_settings", liveSettingKeys()},
            {"camera", cameraJson(state.camera)},
            {"exposure", scene_.image.exposure},
            {"width", scene_.image.width},
            {"height", scene_.image.height}};
}

nlohmann::json SessionControl::pickJson(float x, float y) const {
    const SceneState& state = timeline_.controlled();
    const std::optional<PickHit> hit = pickObject(scene_, state, x, y);
    if (!hit) return {{"ok", true}, {"object", nullptr}};
    return {{"ok", true},
            {"object", scene_.meshes[hit->mesh].name},
            {"mesh", hit->mesh},
            {"point", vec3Json(hit->point)},
            {"distance", hit->distance},
            {"translate", vec3Json(state.transforms[hit->mesh].translate)}};
}

}  // namespace igi
