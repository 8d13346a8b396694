#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>

#include <boost/asio/signal_set.hpp>

#include "AdaptiveTiles.h"
#include "ClientRoster.h"
#include "CodedFrame.h"
#include "ControlServer.h"
#include "FrameCompositor.h"
#include "FrameLogPace.h"
#include "FrameOutputs.h"
#include "LocalClients.h"
#include "MasterOptions.h"
#include "Messages.h"
#include "OpenFrames.h"
#include "ProgressLine.h"
#include "RenderLimits.h"
#include "SceneTimeline.h"
#include "SessionControl.h"
#include "Statistics.h"
#include "TileDecoding.h"
#include "TileScheduler.h"
#include "scene/Scene.h"
#include "scene/SceneLoader.h"
#include "util/ThreadPool.h"

namespace igi {

/// The master: owns the session. It loads the scene, starts its parts and local clients, and
/// runs the frames: it opens them, hands their tiles to the clients, takes the results in,
/// composites each frame when its last tile is in, and ends the session. Its parts:
/// ClientRoster (connections and the handshake), TileScheduler (who renders which tile),
/// decodeTileOnPool (a tile result's way into its frame), prepareJoinerScene (what a joiner is
/// sent), FrameCompositor (filtering and accumulation), FrameOutputs (images, snapshots, the
/// web view), SessionControl (control commands and status), SceneTimeline (the scene's
/// epochs), OpenFrames (the frames in flight) and RenderLimits (when rendering ends).
///
/// All session state lives on one io thread (every connection handler runs there), so it
/// needs no locks; decoding, compositing and encoding run on the thread pool.
class Master : private ClientRoster::Events, private SessionControl::Frames {
  public:
    explicit Master(MasterOptions options);
    ~Master() override;

    /// Runs the whole session; returns the process exit code.
    int run();
    /// Draws this progress line as frames complete (main makes one on a terminal).
    void showProgress(std::shared_ptr<ProgressLine> progress) { progress_ = std::move(progress); }

  private:
    void loadScene();
    /// The tile layout and the open frames for frames made with `settings`, from the next
    /// frame to open.
    void makeFrames(const RenderSettings& settings);
    /// Whether the next frame can be made with the settings in force: after a settings command
    /// that changed how frames are made, once the frames in flight are composited (then it
    /// makes them anew and returns true).
    bool framesFollowSettings();
    std::uint32_t maxTileResultBytes() const;
    void startControl();
    void startLocalClients();
    void writeStatistics();

    // ClientRoster::Events
    void onWelcomed(ConnectedClient& client) override;
    void onReady(ConnectedClient& client, const proto::SceneReady& ready) override;
    void onTileResult(ConnectedClient& client, const proto::Header& header,
                      std::vector<std::uint8_t> payload) override;
    void onLeft(ClientId id, const std::string& reason) override;
    // SessionControl::Frames
    std::uint32_t framesDone() const override { return nextFrameToFinish_ - options_.firstFrame; }
    std::uint32_t nextFrame() const override { return nextFrameToOpen_; }
    void stop() override;
    void setTargetError(double target) override;
    void resume(bool changed) override;
    nlohmann::json errorJson() const override;

    /// Ends the rendering for `why` (RenderLimits::end): the session too, unless it is live.
    void endRendering(const std::string& why);

    void onTileDecoded(const DecodedTile& decoded);
    void onComposited(std::uint32_t frame, double seconds);
    /// Frame `frame` (still in frames_) is in the compositor's image: its stats say so.
    void noteShown(std::uint32_t frame);
    void publishToView(std::uint32_t frame);

    void maybeStart();
    void dispatch();
    void openFramesAsNeeded();
    void finishReadyFrames();
    void endSession(int exitCode);
    void scheduleTick();

    MasterOptions options_;
    boost::asio::io_context io_;
    boost::asio::steady_timer tick_;
    ThreadPool pool_;
    Scene scene_;
    proto::SceneData sceneData_;
    Statistics stats_;
    std::unique_ptr<ClientRoster> roster_;
    std::unique_ptr<TileScheduler> scheduler_;
    std::unique_ptr<FrameCompositor> compositor_;
    std::unique_ptr<SceneTimeline> timeline_;
    std::unique_ptr<FrameOutputs> outputs_;
    std::unique_ptr<SessionControl> sessionControl_;
    std::shared_ptr<ProgressLine> progress_;
    FrameLogPace framePace_;  ///< with options_.paceFrameLines
    boost::asio::signal_set signals_;
    std::int64_t compositedEpoch_ = -1;  ///< epoch of the frame last composited
    RenderSettings frameSettings_;       ///< what the frames are made with (makeFrames)
    std::uint32_t framesMadeAt_ = 0;     ///< the first frame made with frameSettings_
    LocalClients localClients_;
    std::unique_ptr<OpenFrames> frames_;
    std::unique_ptr<AdaptiveTiles> adaptive_;  ///< which tile regions each frame renders
    bool compositing_ = false;
    /// Frames the pool has composited into the image (written by the pool's thread): one may
    /// finish after the session ended, when its io handler no longer runs.
    std::atomic<std::uint32_t> compositedUpTo_{0};
    std::uint32_t nextFrameToOpen_ = 0;
    std::uint32_t nextFrameToFinish_ = 0;
    std::uint64_t ticks_ = 0;
    bool ending_ = false;
    RenderLimits limits_{
        options_};  ///< when rendering ends; started() once the first frame may open
    int exitCode_ = 0;
    std::chrono::steady_clock::time_point created_;
    std::chrono::steady_clock::time_point lastClientSeen_;  ///< last tick with a ready client
};

}  // namespace igi
