#include "ClientRoster.h"
#include "BuildId.h"

#include <algorithm>
#include <cmath>

#include <spdlog/spdlog.h>
#include <boost/asio/ip/address.hpp>

#include "OpenPort.h"

namespace igi {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
}

}  // namespace

ClientRoster::ClientRoster(boost::asio::io_context& io, const MasterOptions& options,
                           Statistics& stats, Events& events, Clock::time_point created)
    : options_(options), stats_(stats), events_(events), created_(created), acceptor_(io) {}

void ClientRoster::setUpSecret() {
    key_ = net::clusterKeyFrom(options_.secretFile);  // --secret-file, else IGI_SECRET
    const bool loopback = boost::asio::ip::make_address(options_.listenHost).is_loopback();
    if (options_.insecure) {
        if (!loopback)
            throw std::invalid_argument("--insecure is for loopback only; listening on " +
                                        options_.listenHost +
                                        " needs a cluster secret (--secret-file or IGI_SECRET)");
        spdlog::warn(
            "INSECURE: no cluster secret; anything that reaches {}:{} may join and feed results",
            options_.listenHost, options_.listenPort);
        key_.reset();
        return;
    }
    if (key_) return;  // local clients get the same --secret-file, or inherit IGI_SECRET
    if (options_.remoteClients > 0 || !loopback)
        throw std::invalid_argument(
            "clients from the network need a cluster secret: --secret-file FILE or "
            "IGI_SECRET (or --insecure, on loopback only)");
    // Local clients only: a fresh secret of this session, handed to them in their environment.
    localSecret_ = net::ClusterKey::randomSecret();
    key_ = net::ClusterKey::fromSecret(localSecret_);
}

void ClientRoster::listen(std::uint64_t seed, std::uint32_t maxTileResultBytes) {
    using boost::asio::ip::tcp;
    seed_ = seed;
    maxTileResultBytes_ = maxTileResultBytes;
    const tcp::endpoint endpoint(boost::asio::ip::make_address(options_.listenHost),
                                 options_.listenPort);
    openPort("--listen", options_.listenHost, options_.listenPort, [&] {
        acceptor_.open(endpoint.protocol());
        acceptor_.set_option(tcp::acceptor::reuse_address(true));
        acceptor_.bind(endpoint);
        acceptor_.listen();
    });
    spdlog::info("listening on {}:{}", options_.listenHost, port());
    accept();
}

std::uint16_t ClientRoster::port() const {
    return acceptor_.local_endpoint().port();
}

net::ConnectionOptions ClientRoster::connectionOptions() const {
    net::ConnectionOptions o;
    o.readTimeout = std::chrono::milliseconds(long(options_.readTimeoutSeconds * 1000));
    // Tile results are decoded on the pool, not on this thread, and can be no bigger than the
    // largest tile needs (under 16 bytes a pixel before compression).
    o.undecodedTypes = {proto::MessageType::TileResult};
    o.payloadLimits = {{proto::MessageType::TileResult, maxTileResultBytes_}};
    return o;
}

void ClientRoster::accept() {
    acceptor_.async_accept(
        [this](const boost::system::error_code& ec, boost::asio::ip::tcp::socket socket) {
            if (ec) {
                if (ec != boost::asio::error::operation_aborted)
                    spdlog::warn("accept failed: {}", ec.message());
                if (!acceptor_.is_open()) return;
            } else if (!ending_) {
                admit(std::move(socket));
            }
            accept();
        });
}

void ClientRoster::admit(boost::asio::ip::tcp::socket socket) {
    socket.set_option(boost::asio::ip::tcp::no_delay(true));
    if (int(clients_.size()) >= options_.maxClients) {
        auto turnedAway = std::make_shared<net::Connection>(std::move(socket), connectionOptions());
        spdlog::warn("turning away {}: {} clients already", turnedAway->peer(), clients_.size());
        turnedAway->send(proto::Error{"the master is full (" + std::to_string(options_.maxClients) +
                                      " clients)"},
                         0, 0);
        turnedAway->closeAfterSending("master full");
        return;
    }
    const ClientId id = nextClientId_++;
    ConnectedClient& c = clients_[id];
    c.id = id;
    c.connected = Clock::now();
    c.nonce = net::ClusterKey::randomNonce();
    c.connection = std::make_shared<net::Connection>(std::move(socket), connectionOptions());
    stats_.client(id).peer = c.connection->peer();
    spdlog::info("client {} connected from {}", id, c.connection->peer());
    c.connection->start(
        [this, id](const proto::Header& h, proto::Message m) { onMessage(id, h, m); },
        [this, id](const std::string& reason) { onClose(id, reason); },
        [this, id](const proto::Header& h, std::vector<std::uint8_t> payload) {
            auto it = clients_.find(id);
            if (it == clients_.end() || ending_) return;
            if (!it->second.ready)
                return refuse(it->second, "a tile result before the scene was ready");
            events_.onTileResult(it->second, h, std::move(payload));
        });
    // First words: what this master runs, and a fresh nonce to prove the secret with.
    c.connection->send(proto::Challenge{proto::kVersion, igi::buildId(), key_.has_value(), c.nonce},
                       0, 0);
}

void ClientRoster::onMessage(ClientId id, const proto::Header&, const proto::Message& message) {
    auto it = clients_.find(id);
    if (it == clients_.end() || ending_) return;
    ConnectedClient& c = it->second;
    if (auto* hello = std::get_if<proto::Hello>(&message)) {
        onHello(c, *hello);
    } else if (auto* error = std::get_if<proto::Error>(&message)) {
        // Also before Hello: a client that refuses this master (another build) says why.
        spdlog::warn("client {} reports: {}", id, error->reason);
    } else if (!c.helloed) {
        refuse(c, "the first message must be Hello");
    } else if (auto* ready = std::get_if<proto::SceneReady>(&message)) {
        if (c.ready) return refuse(c, "a second SceneReady");
        c.ready = true;
        c.lastResult = Clock::now();
        events_.onReady(c, *ready);
    } else if (!std::holds_alternative<proto::Heartbeat>(message)) {
        refuse(c,
               "unexpected " + proto::messageTypeName(proto::typeOf(message)) + " from a client");
    }
}

void ConnectedClient::noteResult(std::chrono::steady_clock::time_point now) {
    const double age = std::chrono::duration<double>(now - lastResult).count();
    lastResult = now;
    tilesPerSecond = tilesPerSecond > 0 ? 0.8 * tilesPerSecond + 0.2 / std::max(age, 1e-4)
                                        : 1.0 / std::max(age, 1e-4);
}

int ConnectedClient::queueDepth() const {
    // Enough tiles to cover ~20 ms of the client's work (latency hiding), and at least two per
    // eight threads so every core has chunks to take.
    const int byRate = int(std::ceil(tilesPerSecond * 0.02));
    return std::clamp(std::max(byRate + 1, 2 + int(threads) / 8), 2, 64);
}

void ClientRoster::refuse(ConnectedClient& c, const std::string& reason) {
    spdlog::warn("closing client {} ({}): {}", c.id, c.connection->peer(), reason);
    c.connection->send(proto::Error{reason}, 0, 0);
    c.connection->closeAfterSending(reason);
}

void ClientRoster::onHello(ConnectedClient& c, const proto::Hello& hello) {
    if (c.helloed) return refuse(c, "a second Hello");
    if (hello.buildId != igi::buildId())
        return refuse(
            c, "client build " + hello.buildId + " does not match master build " + igi::buildId());
    if (key_) {
        // Nothing is given to a peer that cannot prove it holds the cluster secret.
        if (!hello.proof ||
            !net::ClusterKey::same(*hello.proof, key_->clientProof(c.nonce, hello.nonce)))
            return refuse(c,
                          "authentication failed: the client does not hold this cluster's secret");
    }
    c.helloed = true;
    c.host = hello.hostname;
    c.threads = std::max(1u, hello.threads);
    ClientStats& s = stats_.client(c.id);
    s.host = hello.hostname;
    s.threads = hello.threads;
    std::optional<proto::AuthBytes> proof;
    if (key_) proof = key_->masterProof(c.nonce, hello.nonce);
    c.connection->send(proto::Welcome{c.id, seed_, proof}, 0, 0);
    events_.onWelcomed(c);
}

void ClientRoster::onClose(ClientId id, const std::string& reason) {
    auto it = clients_.find(id);
    if (it == clients_.end()) return;
    ClientStats& s = stats_.client(id);
    s.left = true;
    s.leaveReason = reason;
    s.leftSeconds = secondsSince(created_);
    clients_.erase(it);
    events_.onLeft(id, reason);
}

void ClientRoster::dropSilentHandshakes() {
    // A connection that has not proved itself in time is dropped: a slot and a socket are all
    // an anonymous peer gets.
    for (auto& [id, c] : clients_)
        if (!c.helloed && secondsSince(c.connected) > options_.handshakeSeconds &&
            c.connection->isOpen())
            refuse(c, "no valid Hello within " + fmt::format("{:g}", options_.handshakeSeconds) +
                          " s");
}

void ClientRoster::sendHeartbeats() {
    for (auto& [id, c] : clients_) c.connection->send(proto::Heartbeat{}, 0, 0);
}

bool ClientRoster::shutDown() {
    ending_ = true;
    boost::system::error_code ignored;
    acceptor_.close(ignored);
    // Clients close on Shutdown; closing from this side could cut a client off while it still
    // writes a last result, which it would report as an error.
    for (auto& [id, c] : clients_) c.connection->send(proto::Shutdown{}, 0, 0);
    return clients_.empty();
}

void ClientRoster::closeAll(const std::string& reason) {
    for (auto& [id, c] : clients_) c.connection->close(reason);
}

int ClientRoster::readyCount() const {
    return int(std::count_if(clients_.begin(), clients_.end(),
                             [](const auto& e) { return e.second.ready; }));
}

}  // namespace igi
