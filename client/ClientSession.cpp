#include "ClientSession.h"
#include "BuildId.h"

#include <chrono>
#include <thread>

#include <spdlog/spdlog.h>
#include <boost/asio/connect.hpp>
#include <boost/asio/ip/host_name.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>

#include "render/Tile.h"
#include "scene/SceneError.h"
#include "scene/SceneLoader.h"
#include "util/HeapMemory.h"

namespace igi {
namespace {

constexpr auto kHeartbeatPeriod = std::chrono::seconds(2);
// Freed heap goes back to the system every this many heartbeats (20 s): often enough that a
// burst's high water does not stay resident for long, rarely enough to cost nothing.
constexpr std::uint64_t kReleaseHeapEvery = 10;
// Versions kept for tiles still to come.
constexpr std::size_t kKeptVersions = proto::kClientKeptEpochs;

}  // namespace

ClientSession::ClientSession(ClientOptions options)
    : options_(std::move(options)),
      heartbeat_(io_),
      pool_(options_.threads > 0 ? options_.threads : ThreadPool::defaultThreads()) {}

ClientSession::~ClientSession() = default;

bool ClientSession::connect() {
    using boost::asio::ip::tcp;
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::duration<double>(options_.connectTimeoutSeconds);
    auto backoff = std::chrono::milliseconds(50);
    for (;;) {
        boost::system::error_code ec;
        tcp::resolver resolver(io_);
        const auto endpoints = resolver.resolve(options_.host, std::to_string(options_.port), ec);
        tcp::socket socket(io_);
        if (!ec) boost::asio::connect(socket, endpoints, ec);
        if (!ec) {
            socket.set_option(tcp::no_delay(true));
            net::ConnectionOptions connectionOptions;
            connectionOptions.readTimeout =
                std::chrono::milliseconds(long(options_.readTimeoutSeconds * 1000));
            connection_ = std::make_shared<net::Connection>(std::move(socket), connectionOptions);
            return true;
        }
        if (std::chrono::steady_clock::now() >= deadline) {
            spdlog::error("cannot connect to the master at {}:{}: {}", options_.host, options_.port,
                          ec.message());
            return false;
        }
        std::this_thread::sleep_for(backoff);
        backoff = std::min(backoff * 2, std::chrono::milliseconds(1000));
    }
}

int ClientSession::run() {
    try {
        key_ = net::clusterKeyFrom(options_.secretFile);  // --secret-file, else IGI_SECRET
    } catch (const std::invalid_argument& e) {
        spdlog::error("{}", e.what());
        return kRefused;
    }
    if (!key_ && !options_.insecure) {
        spdlog::error(
            "no cluster secret: give --secret-file FILE or IGI_SECRET (or --insecure, for loopback "
            "tests)");
        return kRefused;
    }
    if (!connect()) return kUnreachable;
    spdlog::info("connected to the master at {}", connection_->peer());
    exitCode_ = kLost;
    connection_->start(
        [this](const proto::Header& h, proto::Message m) { onMessage(h, std::move(m)); },
        [this](const std::string& reason) { onClose(reason); });
    // The master speaks first (a Challenge); this client says nothing before it.
    scheduleHeartbeat();
    io_.run();
    return exitCode_;
}

void ClientSession::giveUp(const std::string& reason) {
    exitCode_ = kRefused;
    refuse(reason);
}

void ClientSession::onChallenge(const proto::Challenge& c) {
    if (challenged_) return refuse("a second Challenge");
    challenged_ = true;
    if (c.protocolVersion != proto::kVersion)
        return giveUp("the master speaks protocol " + std::to_string(c.protocolVersion) +
                      ", this client " + std::to_string(proto::kVersion));
    if (c.buildId != igi::buildId())
        return giveUp("the master is build " + c.buildId + ", this client build " + igi::buildId());
    if (c.secretRequired && !key_)
        return giveUp(
            "the master requires the cluster secret: give --secret-file FILE or IGI_SECRET");
    if (!c.secretRequired && !options_.insecure)
        return giveUp(
            "the master runs without a cluster secret and cannot prove who it is; refusing "
            "(--insecure accepts it)");
    nonce_ = net::ClusterKey::randomNonce();
    proto::Hello hello;
    hello.buildId = igi::buildId();
    hello.threads = pool_.size();
    hello.hostname = boost::asio::ip::host_name();
    hello.nonce = nonce_;
    if (c.secretRequired) hello.proof = key_->clientProof(c.nonce, nonce_);
    masterNonce_ = c.nonce;
    requireMasterProof_ = c.secretRequired;
    connection_->send(hello, 0, 0);
}

void ClientSession::onWelcome(const proto::Welcome& w) {
    if (!challenged_ || welcomed_) return refuse("an unexpected Welcome");
    // Work is taken only from a master that proves it holds the secret.
    if (requireMasterProof_ &&
        (!w.proof || !net::ClusterKey::same(*w.proof, key_->masterProof(masterNonce_, nonce_))))
        return giveUp("the master could not prove it holds the cluster secret");
    welcomed_ = true;
    spdlog::info("the master calls this client {}", w.clientId);
}

void ClientSession::scheduleHeartbeat() {
    heartbeat_.expires_after(kHeartbeatPeriod);
    heartbeat_.async_wait([this](const boost::system::error_code& ec) {
        if (ec || !connection_->isOpen()) return;
        connection_->send(proto::Heartbeat{}, 0, 0);
        if (++heartbeats_ % kReleaseHeapEvery == 0) {
            const std::size_t released = releaseFreeHeap();
            // The heap's figures (a walk over every arena) only for the soak's debug log.
            if (spdlog::should_log(spdlog::level::debug)) {
                const HeapFigures heap = heapFigures();
                spdlog::debug(
                    "heap: {:.1f} MB in use, {:.1f} MB held; {:.1f} MB of freed heap released",
                    heap.inUse / 1e6, heap.held / 1e6, released / 1e6);
            }
        }
        scheduleHeartbeat();
    });
}

void ClientSession::onMessage(const proto::Header& header, proto::Message message) {
    if (std::holds_alternative<proto::Heartbeat>(message)) return;  // it only keeps the line alive
    if (auto* error = std::get_if<proto::Error>(&message)) {
        spdlog::error("the master refused this client: {}", error->reason);
        // Refused during the handshake (secret, build, a full master): retrying will not help.
        if (!welcomed_) exitCode_ = kRefused;
        return connection_->close("error from the master");
    }
    if (auto* challenge = std::get_if<proto::Challenge>(&message)) return onChallenge(*challenge);
    if (auto* welcome = std::get_if<proto::Welcome>(&message)) return onWelcome(*welcome);
    if (!welcomed_)
        return refuse(proto::messageTypeName(proto::typeOf(message)) + " before the handshake");
    if (auto* data = std::get_if<proto::SceneData>(&message))
        return onSceneData(header, std::move(*data));
    if (auto* update = std::get_if<proto::SceneUpdate>(&message))
        return onSceneUpdate(header.epoch, header.frame, std::move(update->changes));
    if (auto* tile = std::get_if<proto::TileAssign>(&message)) return onTile(header, *tile);
    if (std::holds_alternative<proto::Shutdown>(message)) {
        spdlog::info("the master ended the session");
        exitCode_ = kShutdown;
        return connection_->close("shutdown");
    }
    refuse("unexpected " + proto::messageTypeName(proto::typeOf(message)) + " from the master");
}

void ClientSession::refuse(const std::string& reason) {
    spdlog::error("closing the connection: {}", reason);
    connection_->send(proto::Error{reason}, 0, 0);
    connection_->closeAfterSending(reason);
}

void ClientSession::onClose(const std::string& reason) {
    if (exitCode_ != 0) spdlog::error("connection to the master closed: {}", reason);
    heartbeat_.cancel();
    pool_.clearPending();  // tiles nobody will receive
    io_.stop();
}

namespace {

// The scene, with the loader's warnings left out when asked. spdlog's level is global: the
// few seconds of loading also hide other threads' warnings, of which a client that has not
// started rendering has none but a lost connection's (which ends the load anyway).
Scene loadBundleQuietlyIf(bool quiet, const SceneBundle& bundle) {
    const spdlog::level::level_enum level = spdlog::get_level();
    if (!quiet || level > spdlog::level::warn) return loadSceneBundle(bundle);
    struct Restore {
        spdlog::level::level_enum level;
        ~Restore() { spdlog::set_level(level); }
    } restore{level};
    spdlog::set_level(spdlog::level::err);
    return loadSceneBundle(bundle);
}

}  // namespace

void ClientSession::onSceneData(const proto::Header& header, proto::SceneData data) {
    if (sceneRequested_) return refuse("a second scene in one session");
    sceneRequested_ = true;
    latestEpoch_ = header.epoch;
    // Loading can take a while for big scenes: do it off the io thread, so heartbeats go on.
    pool_.submit([this, epoch = header.epoch, data = std::move(data)]() mutable {
        try {
            const auto start = std::chrono::steady_clock::now();
            auto scene =
                std::make_unique<Scene>(loadBundleQuietlyIf(!options_.sceneWarnings, data.bundle));
            scene->render = data.settings;
            scene->image = data.image;
            scene->camera = data.camera;
            auto geometry = std::make_unique<SceneGeometry>(device_, *scene);
            if (data.history.size() > epoch)
                throw std::runtime_error(std::to_string(data.history.size()) +
                                         " epochs of history before epoch " +
                                         std::to_string(epoch));
            auto versions = replayHistory(*scene, *geometry, data, epoch);
            const auto& version = versions.back();
            const float seconds =
                std::chrono::duration<float>(std::chrono::steady_clock::now() - start).count();
            const RenderSettings& first = version->renderer.firstFrameSettings();
            spdlog::info(
                "scene '{}' ready: {} triangles in {:.2f} s, {} light paths and {} direct samples "
                "per set{}{}",
                data.bundle.sceneName, version->traceable.triangleCount(), seconds,
                version->renderer.builder().vplPaths(), scene->render.directSamples,
                version->renderer.builder().causticsActive() ? ", caustics on" : "",
                !version->renderer.firstFrameDiffers()
                    ? std::string()
                    : fmt::format("; the first frame after a change: direct samples {}, VPLs "
                                  "per point {}",
                                  first.directSamples, first.indirectVpls));
            boost::asio::post(io_, [this, scene = std::move(scene), geometry = std::move(geometry),
                                    versions = std::move(versions), seconds]() mutable {
                onSceneLoaded(std::move(scene), std::move(geometry), std::move(versions), seconds);
            });
        } catch (const std::exception& e) {
            spdlog::error("cannot build the scene: {}", e.what());
            connection_->send(proto::Error{std::string("cannot build the scene: ") + e.what()}, 0,
                              0);
            connection_->closeAfterSending("scene build failed");
        }
    });
}

std::vector<std::shared_ptr<SceneVersion>> ClientSession::replayHistory(
    const Scene& scene, const SceneGeometry& geometry, const proto::SceneData& data,
    std::uint32_t epoch) {
    // The base epoch's state, then each epoch after it in turn, as the other clients built
    // them from their SceneUpdates: a GI mode that keeps lighting across epochs ends up with
    // the lighting they hold (docs/MODES.md). Without history this is the current epoch alone.
    // The settings in force are the state's: the base's changes carry any `settings` command.
    SceneState state = SceneState::of(scene);
    applyChanges(state, data.changes);
    std::uint32_t e = epoch - std::uint32_t(data.history.size());
    std::vector<std::shared_ptr<SceneVersion>> versions;
    versions.push_back(
        std::make_shared<SceneVersion>(e, geometry, state, state.render, scene.image,
                                       LightingContext{&scene, e, data.baseFirstFrame, nullptr}));
    for (const proto::EpochChanges& next : data.history) {
        applyChanges(state, next.changes);
        ++e;
        auto previous = changesSettings(next.changes)
                            ? nullptr
                            : versions.back()->renderer.method().history(next.firstFrame);
        versions.push_back(std::make_shared<SceneVersion>(
            e, geometry, state, state.render, scene.image,
            LightingContext{&scene, e, next.firstFrame, std::move(previous)}));
        if (versions.size() > kKeptVersions) versions.erase(versions.begin());
    }
    return versions;
}

void ClientSession::onSceneLoaded(std::unique_ptr<Scene> scene,
                                  std::unique_ptr<SceneGeometry> geometry,
                                  std::vector<std::shared_ptr<SceneVersion>> versions,
                                  float seconds) {
    scene_ = std::move(scene);
    geometry_ = std::move(geometry);
    for (const auto& v : versions) versions_[v->epoch] = v;
    const std::uint64_t triangles = versions.back()->traceable.triangleCount();
    ready_ = true;
    for (auto& u : std::exchange(pendingUpdates_, {}))
        onSceneUpdate(u.epoch, u.firstFrame, std::move(u.changes));
    connection_->send(proto::SceneReady{triangles, seconds}, 0, 0);
}

void ClientSession::onSceneUpdate(std::uint32_t epoch, std::uint32_t firstFrame,
                                  std::vector<SceneChange> changes) {
    if (!sceneRequested_) return refuse("a scene update before the scene");
    if (epoch != latestEpoch_ + 1 && ready_)
        return refuse("scene update to epoch " + std::to_string(epoch) + " after epoch " +
                      std::to_string(latestEpoch_));
    if (!ready_) {  // still loading: apply in order once loaded
        pendingUpdates_.push_back({epoch, firstFrame, std::move(changes)});
        return;
    }
    SceneState state = versions_.at(latestEpoch_)->state;
    try {
        applyChanges(state, changes);
    } catch (const std::exception& e) {
        return refuse(std::string("a bad scene update: ") + e.what());
    }
    // Cheap: a top-level commit and the lights (and a batch of photons when streaming); the
    // meshes are shared. Every update reaches every client, so each continues the same history;
    // new settings start it afresh, as a session started with them at this frame would.
    const auto& previous = versions_.at(latestEpoch_)->renderer.method();
    auto history = changesSettings(changes) ? nullptr : previous.history(firstFrame);
    const RenderSettings settings = state.render;
    versions_[epoch] = std::make_shared<SceneVersion>(
        epoch, *geometry_, std::move(state), settings, scene_->image,
        LightingContext{scene_.get(), epoch, firstFrame, std::move(history)});
    latestEpoch_ = epoch;
    // Tiles of old epochs keep their version alive; the map keeps only recent ones.
    while (versions_.size() > kKeptVersions) versions_.erase(versions_.begin());
}

void ClientSession::onTile(const proto::Header& header, const proto::TileAssign& a) {
    if (!ready_) return refuse("a tile before the scene was ready");
    const auto version = versions_.find(header.epoch);
    if (version == versions_.end())
        return refuse("a tile of epoch " + std::to_string(header.epoch) +
                      ", which this client does not have");
    const RenderSettings& s = version->second->state.render;
    const Tile tile{a.x0, a.y0, a.width, a.height, a.kx, a.ky};
    if (a.kx >= s.interleaveX || a.ky >= s.interleaveY || a.x0 % s.interleaveX != 0 ||
        a.y0 % s.interleaveY != 0 || a.x0 + a.width > scene_->image.width ||
        a.y0 + a.height > scene_->image.height)
        return refuse("a tile outside the image or the interleaving pattern");
    if (header.frame > newestFrame_) {
        newestFrame_ = header.frame;
        // Sets of frames two behind are no longer needed: frames are pipelined one deep.
        if (newestFrame_ >= 2)
            for (auto& [epoch, v] : versions_) v->renderer.evictBefore(newestFrame_ - 1);
    }
    const std::uint32_t frame = header.frame, epoch = header.epoch;
    std::shared_ptr<SceneVersion> v = version->second;
    if (options_.replay) return replayTile(v, frame, epoch, a.tileId, tile);
    v->renderer.render(pool_, frame, a.accumulation, a.tileId, tile,
                       [this, v, frame, epoch](proto::TileResult&& result) {
                           connection_->send(result, frame, epoch);
                       });
}

void ClientSession::replayTile(const std::shared_ptr<SceneVersion>& version, std::uint32_t frame,
                               std::uint32_t epoch, std::uint32_t tileId, const Tile& tile) {
    {
        std::lock_guard lock(replayMutex_);
        auto it = recorded_.find(tileId);
        if (it != recorded_.end()) {
            std::vector<std::uint8_t> bytes = it->second;
            proto::setHeaderFrameAndEpoch(bytes, frame, epoch);
            connection_->sendEncoded(std::move(bytes));
            return;
        }
    }
    // Replayed tiles are the first frame's, whatever the accumulation: the master's ceiling is
    // measured, not the image.
    version->renderer.render(pool_, frame, 0, tileId, tile,
                             [this, version, frame, epoch, tileId](proto::TileResult&& result) {
                                 std::vector<std::uint8_t> bytes =
                                     proto::encodeMessage(result, frame, epoch);
                                 {
                                     std::lock_guard lock(replayMutex_);
                                     recorded_[tileId] = bytes;
                                 }
                                 connection_->sendEncoded(std::move(bytes));
                             });
}

}  // namespace igi
