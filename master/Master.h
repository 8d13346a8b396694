#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>

#include <boost/asio/signal_set.hpp>
#include <nlohmann/json.hpp>

#include "CodedFrame.h"
#include "ControlServer.h"
#include "FrameCompositor.h"
#include "FrameLogPace.h"
#include "LocalClients.h"
#include "MasterOptions.h"
#include "Messages.h"
#include "ProgressLine.h"
#include "SceneTimeline.h"
#include "Statistics.h"
#include "TileScheduler.h"
#include "ViewServer.h"
#include "net/ClusterKey.h"
#include "net/Connection.h"
#include "scene/Scene.h"
#include "scene/SceneLoader.h"
#include "util/ThreadPool.h"

namespace igi {

/// The master: owns the session. It loads the scene, listens for clients (and starts local
/// ones), ships them the scene, hands out tiles frame after frame, assembles the results,
/// filters and accumulates them, and writes the image and the statistics.
///
/// All session state lives on one io thread (every connection handler runs there), so it
/// needs no locks; filtering runs on the thread pool.
class Master {
  public:
    explicit Master(MasterOptions options);
    ~Master();

    /// Runs the whole session; returns the process exit code.
    int run();
    /// Draws this progress line as frames complete (main makes one on a terminal).
    void showProgress(std::shared_ptr<ProgressLine> progress) { progress_ = std::move(progress); }

  private:
    struct Session {
        ClientId id = 0;
        std::shared_ptr<net::Connection> connection;
        proto::AuthBytes nonce{};  ///< this connection's challenge
        std::chrono::steady_clock::time_point connected;
        bool helloed = false;
        bool sceneSent = false;  ///< it has the scene: it gets every update from now on
        bool ready = false;
        std::string host;
        std::uint32_t threads = 1;
        double tilesPerSecond = 0;  ///< measured, drives how many tiles it holds
        std::chrono::steady_clock::time_point lastResult;
    };
    struct FrameRecord {
        proto::CodedFrame buffer;
        std::chrono::steady_clock::time_point opened;
        std::uint32_t epoch = 0;  ///< the scene state every tile of it renders
        /// Its place in the accumulation (TileAssign::accumulation): frames since its epoch
        /// began, or 0 without accumulation.
        std::uint32_t accumulation = 0;
        int decoding = 0;          ///< tile results being decoded on the pool
        double decodeSeconds = 0;  ///< pool time spent decoding and scattering its tiles
    };

    void loadScene();
    /// Without --frames, an animation runs to its last keyframe; a shorter --frames is warned.
    void fitFramesToAnimation(const Animation& animation);
    /// The run's settings, for --stats-json.
    nlohmann::json sessionJson() const;
    void setUpSecret();
    std::uint32_t maxTileResultBytes() const;
    void listen();
    void accept();
    void onMessage(ClientId id, const proto::Header& header, const proto::Message& message);
    void onClose(ClientId id, const std::string& reason);
    void onHello(Session& s, const proto::Hello& hello);
    void onSceneReady(Session& s, const proto::SceneReady& ready);
    void onTileResult(Session& s, const proto::Header& header, std::vector<std::uint8_t> payload);
    void onTileDecoded(ClientId id, std::uint32_t frame, std::uint32_t tile,
                       const std::string& error, const proto::TileStats& tileStats,
                       std::uint64_t wireBytes, double seconds);
    void onComposited(std::uint32_t frame, double seconds);
    /// Frame `frame` (still in frames_) is in the compositor's image: its stats say so.
    void noteShown(std::uint32_t frame);
    /// A control command from `from` ("igi-ctl" or "view"): the first's are logged, the view's
    /// (a drag sends dozens a second) only at debug level.
    void onControl(const std::string& line, ControlServer::Reply reply, const char* from);
    void writeFrameImages(std::uint32_t frame);
    void startView();
    /// The newest composited image goes to the view's browsers: tone-mapped and encoded on the
    /// pool, one frame at a time (frames composited meanwhile are skipped, not queued).
    void publishToView(std::uint32_t frame);
    void encodeViewFrame();
    /// The session's state for `status` commands and the view's overlay.
    nlohmann::json statusJson();
    /// The scene's objects, lights and camera as control commands would set them.
    nlohmann::json sceneJson() const;
    nlohmann::json pickJson(float x, float y) const;
    std::string defaultSnapshotPath();
    bool framesLeft(std::uint32_t frame) const {
        return options_.frames == 0 || frame < std::uint32_t(options_.frames);
    }
    void refuse(Session& s, const std::string& reason);

    void maybeStart();
    void dispatch();
    void openFramesAsNeeded();
    int depthFor(const Session& s) const;
    void finishReadyFrames();
    void endSession(int exitCode);
    void scheduleTick();
    int readyClients() const;

    MasterOptions options_;
    boost::asio::io_context io_;
    boost::asio::ip::tcp::acceptor acceptor_;
    boost::asio::steady_timer tick_;
    ThreadPool pool_;
    Scene scene_;
    proto::SceneData sceneData_;
    std::unique_ptr<TileScheduler> scheduler_;
    std::unique_ptr<FrameCompositor> compositor_;
    std::unique_ptr<SceneTimeline> timeline_;
    std::optional<net::ClusterKey> key_;  ///< none: --insecure
    std::string localSecret_;             ///< given to local clients through their environment
    std::unique_ptr<ControlServer> control_;
    std::unique_ptr<ViewServer> view_;
    /// The newest composited image not yet encoded for the view, with its status.
    struct ViewFrame {
        std::shared_ptr<const Image> image;
        std::string status;
        float exposure = 0;
    };
    std::optional<ViewFrame> viewPending_;
    bool viewEncoding_ = false;
    std::shared_ptr<ProgressLine> progress_;
    FrameLogPace framePace_;  ///< with options_.paceFrameLines
    int snapshotsTaken_ = 0;
    boost::asio::signal_set signals_;
    std::int64_t compositedEpoch_ = -1;  ///< epoch of the frame last composited
    std::int64_t openedEpoch_ = -1;      ///< epoch of the frame last opened
    std::uint32_t epochFirstFrame_ = 0;  ///< the first frame of openedEpoch_
    std::uint32_t framesInFlight_ = 2;   ///< frames open at once (from the image size)
    /// A snapshot request waits for the first frame opened after it, so that the image shows
    /// every change commanded before it (frames already open keep their older scene).
    struct Snapshot {
        std::string path;
        ControlServer::Reply reply;
        std::uint32_t fromFrame = 0;
    };
    std::vector<Snapshot> snapshots_;
    Statistics stats_;
    LocalClients localClients_;
    std::map<ClientId, Session> sessions_;
    std::map<std::uint32_t, std::unique_ptr<FrameRecord>> frames_;
    /// Buffers of composited frames, for the frames to come: a fresh one would cost the master
    /// its page faults and clearing every frame (CodedFrame::reuse).
    std::vector<proto::CodedFrame> spareBuffers_;
    bool compositing_ = false;
    /// Frames the pool has composited into the image (written by the pool's thread): one may
    /// finish after the session ended, when its io handler no longer runs.
    std::atomic<std::uint32_t> compositedUpTo_{0};
    ClientId nextClientId_ = 1;
    std::uint32_t nextFrameToOpen_ = 0;
    std::uint32_t nextFrameToFinish_ = 0;
    std::uint64_t ticks_ = 0;
    bool started_ = false;
    bool ending_ = false;
    int exitCode_ = 0;
    std::chrono::steady_clock::time_point created_;
    std::chrono::steady_clock::time_point renderStart_;
    std::chrono::steady_clock::time_point lastClientSeen_;  ///< last tick with a ready client
    std::chrono::steady_clock::time_point renderEnd_;
};

}  // namespace igi
