#pragma once

#include <cstdint>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "Messages.h"
#include "RecentRates.h"
#include "TileScheduler.h"

namespace igi {

/// What one frame cost, summed from its tiles and measured on the master.
struct FrameStats {
    std::uint32_t index = 0;
    double seconds = 0;             ///< from the frame's first tile handed out to its image
    double compositeSeconds = 0;    ///< master time in the discontinuity buffer and accumulation
    double decodeSeconds = 0;       ///< master time decoding tile results (summed over threads)
    std::uint32_t epoch = 0;        ///< the scene state it shows
    std::uint32_t accumulated = 0;  ///< frames in the running mean it was shown as
    std::uint64_t rays = 0;
    std::uint64_t shadowRays = 0;
    std::uint64_t wireBytes = 0;  ///< tile results received for it, headers included
    std::uint64_t pixels = 0;
    std::uint32_t tiles = 0;
    std::uint32_t duplicateTiles = 0;  ///< results dropped because another copy came first
    /// Tiles not handed out: their regions' estimated error was at or below the target
    /// (AdaptiveTiles).
    std::uint32_t tilesLeftOut = 0;
    std::uint32_t setsBuilt = 0;
    double vplsPerSet = 0;     ///< mean over the frame's tiles
    double photonsPerSet = 0;  ///< mean over the frame's tiles
    /// The accumulated image's relMSE estimated without a reference (FrameCompositor), from
    /// two frames in on; with --target-error, the frames and seconds to it (ErrorForecast).
    std::optional<double> estimatedRelMse;
    std::optional<double> framesToTarget;
    std::optional<double> secondsToTarget;
    /// The render settings (as a scene file's "render" section, JSON) a settings command put in
    /// force from this frame on; empty for a frame rendered with its predecessor's settings.
    std::string settings;
    /// Composited and shown. A session stopped mid-frame leaves frames that were in flight
    /// (with tiles counted): they are not reported as frames.
    bool shown = false;
};

/// What one client did over the session.
struct ClientStats {
    ClientId id = 0;
    std::string host;
    std::string peer;
    std::uint32_t threads = 0;
    std::uint64_t tiles = 0;
    std::uint64_t rays = 0;
    std::uint64_t bytes = 0;
    double renderSeconds = 0;  ///< its threads' busy time, summed over threads
    double readySeconds = 0;   ///< when it was ready, from the master's start
    double leftSeconds = -1;   ///< when it left, or -1
    bool left = false;
    std::string leaveReason;
    /// Interleaving sets it got, per frame still open; a closed frame is folded into the
    /// totals below, so that a session of days keeps only the frames in flight.
    std::map<std::uint32_t, std::set<int>> setsByOpenFrame;
    std::uint64_t frames = 0;        ///< closed frames it got tiles of
    std::uint64_t setsInFrames = 0;  ///< distinct sets it got, summed over those frames
    std::int64_t firstFrame = -1;    ///< the first frame it got a tile of
};

/// Collects statistics for --stats-json and the console. Memory stays flat however long the
/// session: a frame's statistics are kept while it is open, and written out (to a sidecar file
/// beside --stats-json, one JSON line per frame) when it closes; the per-client figures are
/// running totals.
class Statistics {
  public:
    Statistics() = default;
    Statistics(const Statistics&) = delete;
    Statistics& operator=(const Statistics&) = delete;
    /// Removes the sidecar of a session that did not get to writeJson (an error exit).
    ~Statistics();

    /// Frames closed from now on go to `framesFile(path)` as they close, for writeJson(path).
    void streamFramesFor(const std::filesystem::path& path);
    /// Where the frames of a --stats-json `path` wait for the end of the session (JSON lines).
    static std::filesystem::path framesFile(const std::filesystem::path& path);

    FrameStats& frame(std::uint32_t index);
    ClientStats& client(ClientId id);
    /// A tile result that completed its tile.
    void addTile(std::uint32_t frame, ClientId client, const proto::TileStats& tile,
                 std::uint64_t wireBytes, std::uint32_t pixels);
    /// A copy of a tile that another client finished first: dropped, but it cost bytes.
    void addDuplicate(std::uint32_t frame, ClientId client, std::uint64_t wireBytes);
    /// A tile of interleaving set k handed to a client.
    void noteAssignment(std::uint32_t frame, ClientId client, int k);
    /// A frame is over (shown, or abandoned when the session ends): it is written out if it was
    /// shown, and forgotten. Frames close in order; a late copy of a tile of a closed frame
    /// counts for its client only.
    void closeFrame(std::uint32_t frame);

    /// Closes the frames still open and writes {"frames": [...], "clients": [...], "fps": ...,
    /// "seconds": ..., "session": session}, the frames from the sidecar (which it removes).
    /// Times are seconds from the master's start; rendering ran from renderStart to renderEnd.
    void writeJson(const std::filesystem::path& path, const nlohmann::json& session,
                   double renderStart, double renderEnd);
    /// One line for people watching.
    std::string summaryLine(std::uint32_t frame) const;
    double fps(double totalSeconds) const;
    /// A frame was shown at `seconds` (from the master's start).
    void noteFrameDone(double seconds);
    /// Frames per second over the last few frames shown.
    double recentFps() const;

    /// Rates over the last half second (RecentRates), at `seconds` from the master's start.
    using Rates = RecentRates::Rates;
    Rates sampleRates(double seconds) const;
    /// Called often (the master's tick): keeps the totals the rates are taken from.
    void noteTime(double seconds);

  private:
    std::map<std::uint32_t, FrameStats> frames_;  ///< the open ones
    std::uint32_t closedBelow_ = 0;               ///< frames before this one are closed
    std::uint64_t shownFrames_ = 0;
    std::filesystem::path framesPath_;  ///< the sidecar, while frames are streamed to it
    std::ofstream framesOut_;
    std::map<ClientId, ClientStats> clients_;
    std::map<std::uint32_t, std::uint64_t> vplSum_, photonSum_;
    std::deque<double> doneTimes_;  ///< when the last frames were shown
    RecentRates::Totals totals() const;
    RecentRates recent_;
};

}  // namespace igi
