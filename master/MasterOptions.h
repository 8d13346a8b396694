#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace igi {

/// Everything igi-master's command line says, as plain data.
struct MasterOptions {
    std::filesystem::path scene;
    std::vector<std::filesystem::path> outputs;  ///< .png and/or .exr, written at the end
    /// .exr written at the end: the accumulated image's estimated relMSE per pixel
    /// (FrameCompositor::pixelRelMse), empty: none.
    std::filesystem::path errorOutput;
    int frames = 1;  ///< 0: until stopped (control "stop", SIGINT or SIGTERM)
    /// Rendering ends once the accumulated image's estimated relMSE (FrameCompositor) is at or
    /// below this (0: no target), or after timeLimitSeconds of rendering (0: no limit), or
    /// after `frames`, whichever comes first.
    double targetError = 0;
    double timeLimitSeconds = 0;
    /// With a target error: tile regions whose estimate is at or below it are not rendered
    /// again until something changes (AdaptiveTiles); --no-adaptive-tiles renders every tile.
    bool adaptiveTiles = true;
    /// The number of the session's first frame: a session started at frame F renders frames
    /// F, F + 1, ... as a session that reached F would (their random numbers depend on the
    /// frame's number). What a settings change at frame F is compared with (docs/ANIMATION.md).
    std::uint32_t firstFrame = 0;
    /// --frames was given; without it, an --animation runs to its last keyframe.
    bool framesGiven = false;
    std::filesystem::path animation;  ///< keyframes applied frame by frame (docs/ANIMATION.md)
    std::string outputSequence;       ///< e.g. out/frame_%04d.png: every frame's image
    /// Only these frames (0-based) of the sequence, when not empty (benchmarks that need the
    /// accumulated image after 1, 2, 4, ... frames of a long run).
    std::vector<std::uint32_t> sequenceFrames;
    bool control = false;  ///< accept control commands (docs/ANIMATION.md)
    std::string controlHost = "127.0.0.1";
    std::uint16_t controlPort = 0;  ///< 0: any free port (logged)
    bool view = false;              ///< serve the web view (docs/VIEW.md)
    std::string viewHost = "127.0.0.1";
    std::uint16_t viewPort = 0;  ///< 0: any free port (logged)
    int localClients = 0;
    int remoteClients = 0;  ///< wait for this many clients from anywhere
    std::string listenHost = "127.0.0.1";
    std::uint16_t listenPort = 0;  ///< 0: any free port (fine when all clients are local)
    std::filesystem::path statsJson;
    /// Scene files may name files outside the scene file's folder (docs/SCENE_FORMAT.md).
    bool allowOutsidePaths = false;
    bool headlight = false;      ///< a light at the camera, beside the scene's own (--headlight)
    unsigned threads = 0;        ///< master threads (0: every hardware thread)
    unsigned clientThreads = 0;  ///< threads of each local client (0: share the machine)
    double waitSeconds = 60;     ///< for the clients to connect and build the scene
    double readTimeoutSeconds = 30;       ///< a client silent this long is dropped
    std::string clientLogLevel = "info";  ///< passed to local clients
    std::filesystem::path secretFile;     ///< the cluster secret (else IGI_SECRET, else see below)
    /// No authentication: only allowed when listening on loopback. Without a secret and without
    /// --insecure, a master with local clients only makes a random secret for them.
    bool insecure = false;
    int maxClients = 64;           ///< connections beyond this are turned away
    double handshakeSeconds = 10;  ///< a connection must prove itself within this
    bool replayClients = false;    ///< local clients replay recorded tiles (igi-client --replay)
    /// A live session on a terminal: one frame line a second, not one a frame (FrameLogPace).
    bool paceFrameLines = false;
    /// Render settings from the command line, as a JSON object in the scene file's "render"
    /// syntax (so both are validated the same way), plus image overrides.
    std::string renderOverridesJson = "{}";
    int width = 0;  ///< 0: as the scene says
    int height = 0;
    bool exposureSet = false;
    float exposure = 0;
};

}  // namespace igi
