// igi-master: runs a rendering session. Loads a scene, gathers render clients (local processes
// and/or clients from the network), renders frames with them and writes the image and
// statistics.
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>
#include <boost/asio/ip/address.hpp>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "BuildId.h"
#include "Master.h"
#include "OutputCheck.h"
#include "ProgressLine.h"
#include "SequencePath.h"
#include "util/HostPort.h"
#include "util/LogLevels.h"

namespace {

// "3x3" -> [3, 3]
nlohmann::json parsePair(const std::string& text, const std::string& option) {
    const auto x = text.find('x');
    try {
        if (x == std::string::npos) throw std::invalid_argument(text);
        std::size_t used = 0;
        const int a = std::stoi(text.substr(0, x), &used);
        if (used != x) throw std::invalid_argument(text);
        const int b = std::stoi(text.substr(x + 1), &used);
        if (used != text.size() - x - 1) throw std::invalid_argument(text);
        return nlohmann::json::array({a, b});
    } catch (const std::exception&) {
        throw CLI::ValidationError(option, "expected NxM, for example 3x3, got '" + text + "'");
    }
}

// Integer options: a fraction or an exponent is refused with one message and one exit code
// (CLI11's own conversion error says "Could not convert" and exits with another).
CLI::Validator wholeNumber() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            std::int64_t value = 0;
            const char* end = text.data() + text.size();
            const auto [ptr, ec] = std::from_chars(text.data(), end, value);
            if (text.empty() || ec != std::errc() || ptr != end)
                return "expected a whole number, got '" + text + "'";
            return "";
        },
        "");
}

// --target-error, --time-limit: a finite number above 0 (CLI11's Range lets "nan" through,
// and "1e" or "abc" would otherwise say only "Could not convert").
CLI::Validator positiveNumber() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            char* end = nullptr;
            const double value = std::strtod(text.c_str(), &end);
            if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(value) ||
                !(value > 0))
                return "expected a number above 0, got '" + text + "'";
            return "";
        },
        "");
}

// A seed: all of 0 .. 2^64 - 1, digits only.
std::uint64_t parseSeed(const std::string& text) {
    std::uint64_t seed = 0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, seed);
    if (text.empty() || ec != std::errc() || ptr != end)
        throw CLI::ValidationError("--seed",
                                   "expected a whole number from 0 to "
                                   "18446744073709551615, got '" +
                                       text + "'");
    return seed;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"igi-master: Instant Global Illumination on a cluster of render clients"};
    app.set_version_flag("--version", igi::buildId(), "print the build identity and exit");
    igi::MasterOptions o;
    std::string scene, listen, logLevel = "info";
    std::vector<std::string> outputs;
    app.add_option("--scene", scene,
                   "scene file (.json), or a bare model (.obj, .gltf, .glb) framed automatically")
        ->required();
    app.add_flag("--allow-outside-paths", o.allowOutsidePaths,
                 "let the scene file name files outside its own folder (relative paths only)");
    app.add_flag("--headlight", o.headlight,
                 "add a light at the camera, beside the scene's own (a bare model without an "
                 "emitter gets one anyway)");
    app.add_option("--output", outputs,
                   "image to write at the end (.png tone-mapped, .exr linear); repeatable");
    app.add_option("--error-output", o.errorOutput,
                   "an .exr of the accumulated image's estimated relMSE per pixel, written at the "
                   "end (docs/ERROR_ESTIMATE.md), the same value in R, G and B");
    auto* framesOpt =
        app.add_option("--frames", o.frames,
                       "frames to render (0: until stopped by igi-ctl stop or a signal; "
                       "default 1, or an --animation's length)")
            ->check(wholeNumber())
            ->check(CLI::Range(0, 1 << 24));
    app.add_option("--first-frame", o.firstFrame,
                   "number the frames from this one: they render as the frames of a session that "
                   "reached it (a settings change there renders as a session started with the new "
                   "settings there)")
        ->check(wholeNumber())
        ->check(CLI::Range(0, 1 << 30));
    app.add_option("--target-error", o.targetError,
                   "stop once the image's estimated relMSE (docs/ERROR_ESTIMATE.md) is at or "
                   "below this, e.g. 0.001")
        ->check(positiveNumber());
    app.add_flag("!--no-adaptive-tiles", o.adaptiveTiles,
                 "with --target-error, render every tile every frame (by default, tile regions "
                 "whose estimated error is at or below the target are not rendered again until "
                 "something changes)");
    app.add_option("--time-limit", o.timeLimitSeconds,
                   "stop after this many seconds of rendering (with --frames and --target-error: "
                   "whichever comes first)")
        ->check(positiveNumber());
    app.add_option("--animation", o.animation,
                   "keyframed changes applied frame by frame (docs/ANIMATION.md)");
    app.add_option("--output-sequence", o.outputSequence,
                   "write every frame, e.g. out/frame_%04d.png (.png or .exr)");
    app.add_option("--sequence-frames", o.sequenceFrames,
                   "write only these frames (0-based, comma-separated) of --output-sequence")
        ->delimiter(',')
        ->check(wholeNumber());
    std::string control;
    auto* controlOpt =
        app.add_option("--control", control,
                       "accept control commands (igi-ctl) on HOST:PORT, e.g. 127.0.0.1:7879");
    std::string view;
    auto* viewOpt = app.add_option(
        "--view", view,
        "serve the web view on HOST:PORT (docs/VIEW.md), e.g. 127.0.0.1:8080; off loopback "
        "it needs the token it prints");
    app.add_option("--local-clients", o.localClients,
                   "igi-client processes to start on this machine")
        ->capture_default_str()
        ->check(wholeNumber())
        ->check(CLI::Range(0, 256));
    app.add_option("--clients", o.remoteClients, "clients from anywhere to wait for")
        ->capture_default_str()
        ->check(wholeNumber())
        ->check(CLI::Range(0, 4096));
    app.add_option("--listen", listen,
                   "HOST:PORT to accept clients on (default 127.0.0.1, any free port; "
                   "port 7878 when --clients is given)");
    app.add_option("--stats-json", o.statsJson, "write per-frame and per-client statistics here");
    app.add_option("--threads", o.threads, "master threads (0: all)")
        ->capture_default_str()
        ->check(wholeNumber());
    app.add_option("--client-threads", o.clientThreads,
                   "threads per local client (0: share the cores)")
        ->capture_default_str()
        ->check(wholeNumber());
    app.add_option("--wait-seconds", o.waitSeconds, "how long to wait for the clients")
        ->capture_default_str();
    app.add_option("--read-timeout", o.readTimeoutSeconds,
                   "drop a client silent this long (seconds)")
        ->capture_default_str();
    app.add_option("--width", o.width,
                   "image width (overrides the scene; alone, the height keeps its aspect ratio)")
        ->check(wholeNumber())
        ->check(CLI::Range(1, 16384));
    app.add_option("--height", o.height,
                   "image height (overrides the scene; alone, the width keeps its aspect ratio)")
        ->check(wholeNumber())
        ->check(CLI::Range(1, 16384));
    auto* exposure = app.add_option("--exposure", o.exposure, "exposure of the PNG in stops");
    app.add_option("--log-level", logLevel, "trace, debug, info, warn, error, critical or off")
        ->capture_default_str()
        ->transform(CLI::IsMember(igi::logLevelNames(), CLI::ignore_case));

    // Render settings: same names, ranges and checks as the scene file's "render" section.
    nlohmann::json render = nlohmann::json::object();
    std::string integrator, interleave, filter;
    auto* integratorOpt = app.add_option("--integrator", integrator, "igi, or path (the reference)")
                              ->check(CLI::IsMember({"igi", "path"}));
    std::string gi;
    auto* giOpt = app.add_option("--gi", gi,
                                 "GI mode: igi (fresh light paths every frame), spt (selective "
                                 "photon tracing: only the path groups a change touches traced "
                                 "again), stream (photon streaming onto surface lights), cache "
                                 "(instant caching: VPL light cached at sites and "
                                 "interpolated) or photonmap (Larsen and Christensen: selective "
                                 "photon emission, final gather at the sites, caustics filtered "
                                 "in screen space); docs/MODES.md")
                      ->check(CLI::IsMember({"igi", "spt", "stream", "cache", "photonmap"}));
    std::string lightSampling;
    auto* lightSamplingOpt =
        app.add_option("--light-sampling", lightSampling,
                       "how a point chooses the lights it samples: power, tree (by each light's "
                       "estimated contribution there), or auto (tree from 8 emitters on)")
            ->check(CLI::IsMember({"auto", "power", "tree"}));
    std::string vplSampling;
    auto* vplSamplingOpt =
        app.add_option("--vpl-sampling", vplSampling,
                       "how a point chooses its indirect VPLs: all (every VPL of its set), "
                       "importance (--vpl-pool VPLs per set, --indirect-vpls of them per point by "
                       "their estimated contribution there), or auto (importance from 8 emitters "
                       "on)")
            ->check(CLI::IsMember({"auto", "all", "importance"}));
    auto* interleaveOpt = app.add_option("--interleave", interleave, "interleaving pattern NxM");
    auto* filterOpt = app.add_option("--filter", filter, "discontinuity buffer size NxM");
    std::string converge, roulette, compensation, progressiveRadius, progressiveFilter,
        poolCaustics;
    auto* convergeOpt =
        app.add_option("--converge", converge,
                       "on: accumulation converges (every mean below on); off: the paper's "
                       "estimator")
            ->check(CLI::IsMember({"on", "off"}));
    auto* rouletteOpt =
        app.add_option("--roulette", roulette, "on: light paths end by Russian roulette")
            ->check(CLI::IsMember({"on", "off"}));
    auto* progressiveRadiusOpt =
        app.add_option("--progressive-radius", progressiveRadius,
                       "on: the caustic radius shrinks as frames accumulate")
            ->check(CLI::IsMember({"on", "off"}));
    auto* progressiveFilterOpt =
        app.add_option("--progressive-filter", progressiveFilter,
                       "on: the discontinuity buffer withdraws where accumulation shows its blur")
            ->check(CLI::IsMember({"on", "off"}));
    std::string photonmapCaustics;
    auto* photonmapCausticsOpt =
        app.add_option("--photonmap-caustics", photonmapCaustics,
                       "--gi photonmap: caustics filtered in screen space (the paper's) or "
                       "gathered from the hashed grid (IGI's)")
            ->check(CLI::IsMember({"screen", "grid"}));
    auto* poolCausticsOpt =
        app.add_option("--pool-caustics", poolCaustics,
                       "on: accumulated frames gather every set's caustic photons at each pixel")
            ->check(CLI::IsMember({"on", "off"}));
    auto* compensationOpt = app.add_option("--clamp-compensation", compensation,
                                           "what restores the energy the VPL bound removes")
                                ->check(CLI::IsMember({"off", "shrink", "kollig-keller"}));
    struct Numeric {
        const char* flag;
        const char* key;
        bool integer;  // integer keys must reach the JSON checks as integers
        const char* help;
        double value = 0;
        CLI::Option* option = nullptr;
    };
    std::vector<Numeric> numerics = {
        {"--spp", "path_samples", true, "--integrator path: samples per pixel per frame"},
        {"--direct-samples", "direct_samples", true,
         "light samples per set (shadow rays per pixel) among the lights that are not exact (a "
         "scene's point, spot and sun lights, when at most 4, get one each: docs/LIGHTS.md)"},
        {"--vpl-paths", "vpl_paths", true, "light paths per set (0: from --indirect-vpls)"},
        {"--indirect-vpls", "indirect_vpls", true,
         "wanted indirect VPLs per set (per point with --vpl-sampling importance)"},
        {"--vpl-pool", "vpl_pool", true,
         "VPLs per set that points choose from with --vpl-sampling importance (0: 8 x "
         "--indirect-vpls)"},
        {"--first-frame-divisor", "first_frame_divisor", true,
         "the first frame after a change (every frame without accumulation) takes the light "
         "samples and the VPLs per point divided by this, rounded up (1: all; 0: auto, 4 where "
         "points choose VPLs by importance, else 1)"},
        {"--max-light-path-length", "max_light_path_length", true, "vertices of a light path"},
        {"--clamp-distance", "clamp_distance", false, "VPL clamp, fraction of the scene diagonal"},
        {"--caustic-photons", "caustic_photons", true, "caustic photons per set"},
        {"--caustic-radius", "caustic_radius", false,
         "photon gathering radius, fraction of the scene diagonal"},
        {"--max-eye-depth", "max_eye_depth", true, "specular bounces followed by eye paths"},
        {"--light-edge-rays", "light_edge_rays", true,
         "eye rays per pixel and frame that gather the light seen directly where a light's "
         "outline crosses the pixel (0: off; docs/ACCURACY.md)"},
        {"--filter-depth-threshold", "filter_depth_threshold", false,
         "relative depth difference that splits"},
        {"--filter-normal-threshold", "filter_normal_threshold", false,
         "normal cosine below which neighbours split"},
        {"--max-path-length", "max_path_length", true, "path tracer's maximum path length"},
        {"--roulette-max-length", "roulette_max_length", true,
         "safety cap on light path vertices under roulette"},
        {"--glossy-bound", "glossy_bound", false,
         "sharpness budget of VPL connections (1 and more; glossy lobes beyond it are sampled)"},
        {"--indirect-caustic-photons", "indirect_caustic_photons", true,
         "photons shot from the VPLs at mirrors and glass per set"},
        {"--indirect-caustic-radius", "indirect_caustic_radius", false,
         "their gathering radius, fraction of the scene diagonal"},
        {"--progressive-alpha", "progressive_alpha", false,
         "how fast the caustic radius (and a shrinking clamp) shrinks, in (0, 1)"},
        {"--stream-vsls", "stream_vsls", true, "--gi stream: surface lights on the geometry"},
        {"--stream-photons", "stream_photons", true,
         "--gi stream: light paths shot into the pool per scene epoch"},
        {"--stream-window", "stream_window", true,
         "--gi stream: epochs whose photons the pool holds"},
        {"--spt-groups", "spt_groups", true, "--gi spt: light path groups"},
        {"--spt-paths", "spt_paths", true, "--gi spt: light paths per group"},
        {"--spt-pilots", "spt_pilots", true,
         "--gi spt: pilot paths per group, traced on every change to detect it"},
        {"--spt-budget", "spt_budget", true, "--gi spt: groups traced again per frame at most"},
        {"--cache-spacing", "cache_spacing", false,
         "--gi cache, photonmap: distance between cache sites, fraction of the scene diagonal"},
        {"--cache-radius", "cache_radius", false,
         "--gi cache, photonmap: interpolation radius, in site spacings"},
        {"--photonmap-groups", "photonmap_groups", true,
         "--gi photonmap: photon groups of the selective emission"},
        {"--photonmap-photons", "photonmap_photons", true,
         "--gi photonmap: photons per group (one of each checked per frame)"},
        {"--photonmap-neighbours", "photonmap_neighbours", true,
         "--gi photonmap: photon hits in a radiance estimate"},
        {"--photonmap-gather", "photonmap_gather", true,
         "--gi photonmap: final gather rays per site"},
        {"--tile-size", "tile_size", true, "tile edge in pixels of one k"},
    };
    for (auto& n : numerics) {
        n.option = app.add_option(n.flag, n.value, n.help);
        if (n.integer) n.option->type_name("INT")->check(wholeNumber());
    }
    // An integer of its own: through a double, seeds above 2^53 lost bits.
    std::string seedText;
    auto* seedOpt =
        app.add_option("--seed", seedText, "session seed of every random bit vector, 0 .. 2^64 - 1")
            ->type_name("INT");
    app.add_option(
        "--secret-file", o.secretFile,
        "the cluster secret (else the IGI_SECRET environment variable; with local clients only, "
        "a random one)");
    app.add_flag("--insecure", o.insecure, "no authentication at all (loopback only; for tests)");
    app.add_option("--max-clients", o.maxClients, "connections beyond this are turned away")
        ->capture_default_str()
        ->check(wholeNumber())
        ->check(CLI::Range(1, 4096));
    app.add_option("--handshake-timeout", o.handshakeSeconds,
                   "seconds a new connection has to prove it holds the secret")
        ->capture_default_str()
        ->check(CLI::Range(0.5, 3600.0));
    app.add_flag(
        "--replay-clients", o.replayClients,
        "local clients render each tile once and then resend it: measures the master's ceiling");
    bool noAccumulate = false;
    app.add_flag("--no-accumulate", noAccumulate,
                 "show each frame alone instead of their running mean");
    CLI11_PARSE(app, argc, argv);

    // On a terminal, a finite run draws a progress line under the log (before the pattern is
    // set: it replaces the logger's sink).
    // A target or a time limit ends a run too: it gets the line (with no frame total).
    const bool limited = o.targetError > 0 || o.timeLimitSeconds > 0;
    auto progress = igi::ProgressLine::attachIfTerminal(o.frames, limited);
    // A live session logs a frame line a second (every frame's line is at debug level), on a
    // terminal and in a log file alike: a line a frame fills a log without end.
    o.paceFrameLines = o.frames == 0 && !limited;
    spdlog::set_level(spdlog::level::from_str(logLevel));
    spdlog::set_pattern("[%H:%M:%S.%e] [master] [%l] %v");
    o.scene = scene;
    o.framesGiven = framesOpt->count() > 0;
    // Under a progress line, local clients' info lines (connected, ready, done: the master
    // says as much) would cut into it; their warnings and errors still show.
    o.clientLogLevel = progress && spdlog::level::from_str(logLevel) < spdlog::level::warn
                           ? std::string("warn")
                           : logLevel;
    for (const auto& out : outputs) o.outputs.emplace_back(out);
    o.exposureSet = exposure->count() > 0;
    try {
        if (integratorOpt->count()) render["integrator"] = integrator;
        if (giOpt->count()) render["gi"] = gi;
        if (lightSamplingOpt->count()) render["light_sampling"] = lightSampling;
        if (vplSamplingOpt->count()) render["vpl_sampling"] = vplSampling;
        if (interleaveOpt->count()) render["interleave"] = parsePair(interleave, "--interleave");
        if (filterOpt->count()) render["filter"] = parsePair(filter, "--filter");
        if (convergeOpt->count()) render["converge"] = converge == "on";
        if (rouletteOpt->count()) render["roulette"] = roulette == "on";
        if (compensationOpt->count()) render["clamp_compensation"] = compensation;
        if (progressiveRadiusOpt->count()) render["progressive_radius"] = progressiveRadius == "on";
        if (progressiveFilterOpt->count()) render["progressive_filter"] = progressiveFilter == "on";
        if (poolCausticsOpt->count()) render["pool_caustics"] = poolCaustics == "on";
        if (photonmapCausticsOpt->count()) render["photonmap_caustics"] = photonmapCaustics;
        for (const auto& n : numerics) {
            if (!n.option->count()) continue;
            if (n.integer)
                render[n.key] = static_cast<std::int64_t>(n.value);
            else
                render[n.key] = n.value;
        }
        if (seedOpt->count()) render["seed"] = parseSeed(seedText);
        if (noAccumulate) render["accumulate"] = false;
    } catch (const CLI::Error& e) {
        return app.exit(e);
    }
    o.renderOverridesJson = render.dump();
    try {
        if (listen.empty()) {
            o.listenPort = o.remoteClients > 0 ? 7878 : 0;
        } else {
            const igi::HostPort hp = igi::parseHostPort(listen, "--listen");
            o.listenHost = hp.host;
            o.listenPort = hp.port;
        }
        if (controlOpt->count()) {
            const igi::HostPort hp = igi::parseHostPort(control, "--control");
            o.control = true;
            o.controlHost = hp.host;
            o.controlPort = hp.port;
            // Control commands are not authenticated (docs/SECURITY.md): whoever reaches the
            // port can stop the session or move the scene, so it stays on this machine.
            boost::system::error_code ec;
            const auto address = boost::asio::ip::make_address(hp.host, ec);
            if (hp.host != "localhost" && (ec || !address.is_loopback()))
                throw std::invalid_argument(
                    "--control " + control +
                    ": control commands are not authenticated, so the control port listens on "
                    "loopback only (reach it from elsewhere through an SSH tunnel)");
        }
        if (viewOpt->count()) {
            const igi::HostPort hp = igi::parseHostPort(view, "--view");
            o.view = true;
            o.viewHost = hp.host == "localhost" ? "127.0.0.1" : hp.host;
            o.viewPort = hp.port;
            boost::system::error_code ec;
            boost::asio::ip::make_address(o.viewHost, ec);
            if (ec)
                throw std::invalid_argument("--view " + view + ": '" + hp.host +
                                            "' is not an IP address of this machine");
        }
        // Every file the run will write, checked before the first frame: a mistake found
        // after an hour of rendering costs the hour.
        for (const auto& out : o.outputs) igi::checkImageOutput(out, "--output");
        if (!o.errorOutput.empty()) igi::checkErrorOutput(o.errorOutput);
        if (!o.outputSequence.empty()) {
            igi::checkSequencePattern(o.outputSequence);
            igi::checkImageOutput(igi::sequencePath(o.outputSequence, 0), "--output-sequence");
        }
        if (!o.statsJson.empty()) igi::checkWritableFolder(o.statsJson, "--stats-json");
    } catch (const std::invalid_argument& e) {
        spdlog::error("{}", e.what());
        return 2;
    }
    if (o.localClients + o.remoteClients == 0) {
        spdlog::error("no clients: give --local-clients N and/or --clients N");
        return 2;
    }
    try {
        igi::Master master(o);
        master.showProgress(progress);
        return master.run();
    } catch (const std::exception& e) {
        spdlog::error("{}", e.what());
        return 1;
    }
}
