#pragma once

#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>

#include "EmbreeDevice.h"
#include "Messages.h"
#include "TileRenderer.h"
#include "TraceableScene.h"
#include "net/Connection.h"
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
    void onClose(const std::string& reason);
    void onSceneData(proto::SceneData data);
    void onTile(const proto::Header& header, const proto::TileAssign& assign);
    void replayTile(std::uint32_t frame, std::uint32_t epoch, std::uint32_t tileId,
                    const Tile& tile);

    void scheduleHeartbeat();

    ClientOptions options_;
    boost::asio::io_context io_;
    boost::asio::steady_timer heartbeat_;
    std::shared_ptr<net::Connection> connection_;
    EmbreeDevice device_;
    std::unique_ptr<Scene> scene_;
    std::unique_ptr<TraceableScene> traceable_;
    std::unique_ptr<TileRenderer> renderer_;
    std::atomic<bool> ready_{false};
    std::uint32_t newestFrame_ = 0;
    int exitCode_ = 1;
    std::mutex replayMutex_;
    std::map<std::uint32_t, std::vector<std::uint8_t>> recorded_;  ///< encoded results, by tile
    // Last, so it is destroyed (its threads joined) before the scene its tasks use.
    ThreadPool pool_;
};

}  // namespace igi
