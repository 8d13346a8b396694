#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>

#include "MasterOptions.h"
#include "Messages.h"
#include "Statistics.h"
#include "net/ClusterKey.h"
#include "net/Connection.h"

namespace igi {

/// One client's connection as the master sees it.
struct ConnectedClient {
    ClientId id = 0;
    std::shared_ptr<net::Connection> connection;
    proto::AuthBytes nonce{};  ///< this connection's challenge
    std::chrono::steady_clock::time_point connected;
    bool helloed = false;
    bool sceneSent = false;  ///< it has the scene: it gets every update from now on
    /// The first frame it may render: the first open frame of an epoch it holds
    /// (TileScheduler::next). A joiner gets every epoch of the frames open when it joins
    /// (SceneTimeline::Join), so this bound only bites when more epochs are open than a client
    /// keeps.
    std::uint32_t firstFrame = 0;
    bool ready = false;
    std::string host;
    std::uint32_t threads = 1;
    double tilesPerSecond = 0;  ///< measured, drives how many tiles it holds
    std::chrono::steady_clock::time_point lastResult;

    /// A result came in at `now`: tilesPerSecond follows the rate at which they come.
    void noteResult(std::chrono::steady_clock::time_point now);
    /// How many tiles it is to hold at once (queueDepth).
    int queueDepth() const;
};

/// The master's clients: it listens, turns away connections beyond --max-clients, proves the
/// cluster secret both ways (docs/SECURITY.md), and refuses any client that breaks the
/// handshake's order. What a client says once it is in (it is ready, a tile result) and that it
/// left go to the session through `Events`. Runs on the master's io thread, like every handler.
class ClientRoster {
  public:
    /// What the session does when a client moves on.
    class Events {
      public:
        virtual ~Events() = default;
        /// It proved the secret and was welcomed: send it the scene.
        virtual void onWelcomed(ConnectedClient& client) = 0;
        virtual void onReady(ConnectedClient& client, const proto::SceneReady& ready) = 0;
        /// Undecoded: tile results are decoded on the pool.
        virtual void onTileResult(ConnectedClient& client, const proto::Header& header,
                                  std::vector<std::uint8_t> payload) = 0;
        /// It is gone (no longer in the roster).
        virtual void onLeft(ClientId id, const std::string& reason) = 0;
    };

    /// `created`: when the session began (the statistics' clock).
    ClientRoster(boost::asio::io_context& io, const MasterOptions& options, Statistics& stats,
                 Events& events, std::chrono::steady_clock::time_point created);

    /// The cluster secret from --secret-file or IGI_SECRET, --insecure, or a fresh one for local
    /// clients only; throws std::invalid_argument when the options cannot be met.
    void setUpSecret();
    /// Starts accepting. `seed` goes to each client in its Welcome; a tile result larger than
    /// `maxTileResultBytes` closes its connection before it is read.
    void listen(std::uint64_t seed, std::uint32_t maxTileResultBytes);
    std::uint16_t port() const;
    /// The secret made for local clients (empty when there is none), for their environment.
    const std::string& localSecret() const { return localSecret_; }

    /// Closes a client's connection, telling it why (and logging it).
    void refuse(ConnectedClient& client, const std::string& reason);
    /// Drops connections that have not proved themselves within --handshake-seconds.
    void dropSilentHandshakes();
    void sendHeartbeats();
    /// No more connections; every client is asked to shut down. Returns true when none is left.
    bool shutDown();
    /// Closes the connections of clients that did not shut down.
    void closeAll(const std::string& reason);

    int readyCount() const;
    bool empty() const { return clients_.empty(); }
    std::size_t size() const { return clients_.size(); }
    std::map<ClientId, ConnectedClient>& clients() { return clients_; }
    const std::map<ClientId, ConnectedClient>& clients() const { return clients_; }

  private:
    void accept();
    net::ConnectionOptions connectionOptions() const;
    void admit(boost::asio::ip::tcp::socket socket);
    void onMessage(ClientId id, const proto::Header& header, const proto::Message& message);
    void onHello(ConnectedClient& client, const proto::Hello& hello);
    void onClose(ClientId id, const std::string& reason);

    const MasterOptions& options_;
    Statistics& stats_;
    Events& events_;
    std::chrono::steady_clock::time_point created_;
    boost::asio::ip::tcp::acceptor acceptor_;
    std::optional<net::ClusterKey> key_;  ///< none: --insecure
    std::string localSecret_;
    std::uint64_t seed_ = 0;
    std::uint32_t maxTileResultBytes_ = 0;
    bool ending_ = false;
    ClientId nextClientId_ = 1;
    std::map<ClientId, ConnectedClient> clients_;
};

}  // namespace igi
