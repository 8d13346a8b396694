#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>

#include "Messages.h"
#include "SceneVersion.h"
#include "net/ClusterKey.h"
#include "net/Connection.h"
#include "tracing/EmbreeDevice.h"
#include "tracing/SceneGeometry.h"
#include "util/ThreadPool.h"

namespace igi {

struct ClientOptions {
    std::string host = "127.0.0.1";
    std::uint16_t port = 0;
    unsigned threads = 0;               ///< 0: every hardware thread
    double connectTimeoutSeconds = 30;  ///< keep trying to reach the master this long
    double readTimeoutSeconds = 30;     ///< a master silent this long is considered gone
    /// Renders each tile once, then answers every later request for it with the recorded
    /// result: a client as fast as the network, to measure the master's ceiling.
    bool replay = false;
    std::filesystem::path secretFile;  ///< the cluster secret (else IGI_SECRET)
    bool insecure = false;             ///< join a master without a secret (loopback tests)
    double reconnectSeconds = 60;      ///< after losing the master, try again this long (0: exit)
    /// Log the scene loader's warnings. A master's local clients load the bundle it loaded
    /// and logged already, into the same terminal: there they would repeat each warning.
    bool sceneWarnings = true;
};

/// How a session ended (the process exit code).
enum ClientExit : int {
    kShutdown = 0,     ///< the master ended the session
    kLost = 1,         ///< the connection broke
    kUnreachable = 2,  ///< no master answered, or a setup error
    kRefused = 3,      ///< the handshake failed: wrong secret, other build: retrying is pointless
};

/// A render client's whole life: connect to the master, say hello, receive the scene, build
/// the Embree scene, then render the tiles the master sends on all cores and send the results
/// back, until the master says the session is over.
class ClientSession {
  public:
    explicit ClientSession(ClientOptions options);
    ~ClientSession();

    /// Runs the session; returns the process exit code (0 after a Shutdown from the master).
    int run();

  private:
    bool connect();
    void onMessage(const proto::Header& header, proto::Message message);
    void onChallenge(const proto::Challenge& challenge);
    void onWelcome(const proto::Welcome& welcome);
    /// A problem retrying cannot solve: say it, and end with kRefused.
    void giveUp(const std::string& reason);
    void onClose(const std::string& reason);
    /// The master broke the protocol: say why, then close.
    void refuse(const std::string& reason);
    void onSceneData(const proto::Header& header, proto::SceneData data);
    void onSceneLoaded(std::unique_ptr<Scene> scene, std::unique_ptr<SceneGeometry> geometry,
                       std::vector<std::shared_ptr<SceneVersion>> versions, float seconds);
    /// The versions of a joining client (the newest kKeptVersions): the SceneData's base epoch
    /// and every epoch of its history, each continuing the lighting of the one before.
    static std::vector<std::shared_ptr<SceneVersion>> replayHistory(const Scene& scene,
                                                                    const SceneGeometry& geometry,
                                                                    const proto::SceneData& data,
                                                                    std::uint32_t epoch);
    /// `firstFrame`: the frame the epoch begins at (the update's header frame).
    void onSceneUpdate(std::uint32_t epoch, std::uint32_t firstFrame,
                       std::vector<SceneChange> changes);
    void onTile(const proto::Header& header, const proto::TileAssign& assign);
    void replayTile(const std::shared_ptr<SceneVersion>& version, std::uint32_t frame,
                    std::uint32_t epoch, std::uint32_t tileId, const Tile& tile);

    /// Sends a heartbeat every kHeartbeatPeriod, and gives the heap's free pages back to the
    /// system every few (releaseFreeHeap).
    void scheduleHeartbeat();

    ClientOptions options_;
    boost::asio::io_context io_;
    boost::asio::steady_timer heartbeat_;
    std::uint64_t heartbeats_ = 0;
    std::shared_ptr<net::Connection> connection_;
    std::optional<net::ClusterKey> key_;
    proto::AuthBytes nonce_{};
    proto::AuthBytes masterNonce_{};
    bool requireMasterProof_ = true;
    bool challenged_ = false;
    bool welcomed_ = false;  ///< the master proved itself: work may come
    EmbreeDevice device_;
    // (the members below are used on the io thread only, but for the device and the pool)
    std::unique_ptr<Scene> scene_;             ///< as loaded from the bundle
    std::unique_ptr<SceneGeometry> geometry_;  ///< shared by every version
    /// Versions by epoch (io thread only). Tiles keep the version they render with alive.
    std::map<std::uint32_t, std::shared_ptr<SceneVersion>> versions_;
    std::uint32_t latestEpoch_ = 0;
    /// Updates that arrived while the scene was still loading, applied once it is.
    struct PendingUpdate {
        std::uint32_t epoch, firstFrame;
        std::vector<SceneChange> changes;
    };
    std::vector<PendingUpdate> pendingUpdates_;
    bool sceneRequested_ = false;  ///< SceneData arrived (io thread)
    bool ready_ = false;           ///< the scene is loaded (io thread)
    std::uint32_t newestFrame_ = 0;
    int exitCode_ = kLost;
    std::mutex replayMutex_;
    std::map<std::uint32_t, std::vector<std::uint8_t>> recorded_;  ///< encoded results, by tile
    // Last, so it is destroyed (its threads joined) before the scene its tasks use.
    ThreadPool pool_;
};

}  // namespace igi
