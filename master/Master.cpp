#include "Master.h"

#include <algorithm>
#include <cmath>

#include <spdlog/spdlog.h>
#include <boost/asio/ip/address.hpp>
#include <boost/asio/post.hpp>
#include <nlohmann/json.hpp>

#include "Codec.h"
#include "ControlCommand.h"
#include "ScenePick.h"
#include "SequencePath.h"
#include "ViewPage.h"
#include "image/ImageIO.h"
#include "image/JpegEncoder.h"
#include "render/Tile.h"
#include "scene/RenderSettingsJson.h"
#include "scene/SceneError.h"

namespace igi {
namespace {

using Clock = std::chrono::steady_clock;

/// The epochs of history a joining client replays to hold the lighting the others hold:
/// photon streaming's pool spans the last stream_window epochs (the oldest of which a joiner
/// fills whole, as every client filled epoch 0); selective photon tracing's depends on every
/// epoch since the session began, and so does simulated photon mapping's emission (each frame
/// checks photons round robin); IGI keeps nothing, and instant caching's records are a
/// function of the current state alone (a joiner computes them anew, to the same bits).
std::uint32_t joinHistoryDepth(const RenderSettings& s) {
    if (s.integrator == IntegratorKind::Path) return 0;
    switch (s.gi) {
        case GiMode::Stream:
            return std::uint32_t(std::max(0, s.streamWindow - 1));
        case GiMode::Spt:
        case GiMode::PhotonMap:
            return proto::kMaxHistoryEpochs;
        case GiMode::Igi:
        case GiMode::Cache:
            break;
    }
    return 0;
}
constexpr auto kTickPeriod = std::chrono::milliseconds(20);
// A tile is copied to an idle client only after it has been out at least this long (and three
// times its holder's usual latency, see TileScheduler): short enough to get past a stalled
// client, long enough not to duplicate every tile at the end of a frame.
constexpr double kDuplicateAfterSeconds = 0.05;
// Frames open at once. A frame's last tiles wait on its slowest holders; while they do, the
// other clients work on the next frames. With two, 16 clients each capped to a sixteenth of a
// core idled in every frame's tail and reached 60-70 % of linear scaling; with four, linear
// (scripts/bench_performance.sh, docs/PERFORMANCE.md).
constexpr std::uint32_t kFramesInFlight = 4;
// Each open frame holds a full-size CodedFrame: big images open fewer frames (never fewer
// than two, which pipelining needs) to keep these buffers within this budget.
constexpr std::size_t kOpenFrameBufferBudget = std::size_t{1} << 30;
constexpr std::size_t kFrameBufferBytesPerPixel = proto::CodedFrame::kBytesPerPixel;

double secondsSince(Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
}

}  // namespace

Master::Master(MasterOptions options)
    : options_(std::move(options)),
      acceptor_(io_),
      tick_(io_),
      pool_(options_.threads > 0 ? options_.threads : ThreadPool::defaultThreads()),
      signals_(io_, SIGINT, SIGTERM),
      created_(Clock::now()) {}

Master::~Master() = default;

void Master::loadScene() {
    SceneBundle bundle;
    SceneLoadOptions loadOptions;
    loadOptions.allowOutsidePaths = options_.allowOutsidePaths;
    scene_ = loadSceneFile(options_.scene, &bundle, loadOptions);
    applyRenderSettingsJson(nlohmann::json::parse(options_.renderOverridesJson), scene_.render,
                            "command line", "/render");
    if (options_.width > 0) scene_.image.width = options_.width;
    if (options_.height > 0) scene_.image.height = options_.height;
    if (options_.exposureSet) scene_.image.exposure = options_.exposure;
    sceneData_.bundle = std::move(bundle);
    sceneData_.settings = scene_.render;
    sceneData_.image = scene_.image;
    sceneData_.camera = scene_.camera;
    std::unique_ptr<Animation> animation;
    if (!options_.animation.empty())
        animation = std::make_unique<Animation>(Animation::load(options_.animation, scene_));
    timeline_ = std::make_unique<SceneTimeline>(SceneState::of(scene_), std::move(animation),
                                                joinHistoryDepth(scene_.render));

    const RenderSettings& s = scene_.render;
    auto layout = makeTiles(scene_.image.width, scene_.image.height, s.interleaveX, s.interleaveY,
                            s.tileSize);
    scheduler_ = std::make_unique<TileScheduler>(std::move(layout), s.setCount());
    const std::size_t frameBytes = kFrameBufferBytesPerPixel * std::size_t(scene_.image.width) *
                                   std::size_t(scene_.image.height);
    framesInFlight_ = std::uint32_t(
        std::clamp<std::size_t>(kOpenFrameBufferBudget / frameBytes, 2, kFramesInFlight));
    compositor_ =
        std::make_unique<FrameCompositor>(scene_.image.width, scene_.image.height, s, pool_);
    spdlog::info(
        "scene {}: {} meshes, {} materials, {}x{} pixels, {} tiles per frame, {} integrator",
        options_.scene.string(), scene_.meshes.size(), scene_.materials.size(), scene_.image.width,
        scene_.image.height, scheduler_->layout().size(),
        s.integrator == IntegratorKind::Path ? "path" : "IGI");
}

void Master::listen() {
    using boost::asio::ip::tcp;
    const tcp::endpoint endpoint(boost::asio::ip::make_address(options_.listenHost),
                                 options_.listenPort);
    acceptor_.open(endpoint.protocol());
    acceptor_.set_option(tcp::acceptor::reuse_address(true));
    acceptor_.bind(endpoint);
    acceptor_.listen();
    spdlog::info("listening on {}:{}", options_.listenHost, acceptor_.local_endpoint().port());
    accept();
}

void Master::accept() {
    acceptor_.async_accept([this](const boost::system::error_code& ec,
                                  boost::asio::ip::tcp::socket socket) {
        if (ec) {
            if (ec != boost::asio::error::operation_aborted)
                spdlog::warn("accept failed: {}", ec.message());
            if (!acceptor_.is_open()) return;
        } else if (!ending_) {
            socket.set_option(boost::asio::ip::tcp::no_delay(true));
            net::ConnectionOptions connectionOptions;
            connectionOptions.readTimeout =
                std::chrono::milliseconds(long(options_.readTimeoutSeconds * 1000));
            // Tile results are decoded on the pool, not on this thread, and can be no bigger
            // than the largest tile needs (under 16 bytes a pixel before compression).
            connectionOptions.undecodedTypes = {proto::MessageType::TileResult};
            connectionOptions.payloadLimits = {
                {proto::MessageType::TileResult, maxTileResultBytes()}};
            if (int(sessions_.size()) >= options_.maxClients) {
                auto turnedAway =
                    std::make_shared<net::Connection>(std::move(socket), connectionOptions);
                spdlog::warn("turning away {}: {} clients already", turnedAway->peer(),
                             sessions_.size());
                turnedAway->send(proto::Error{"the master is full (" +
                                              std::to_string(options_.maxClients) + " clients)"},
                                 0, 0);
                turnedAway->closeAfterSending("master full");
                return accept();
            }
            const ClientId id = nextClientId_++;
            Session& s = sessions_[id];
            s.id = id;
            s.connected = Clock::now();
            s.nonce = net::ClusterKey::randomNonce();
            s.connection = std::make_shared<net::Connection>(std::move(socket), connectionOptions);
            stats_.client(id).peer = s.connection->peer();
            spdlog::info("client {} connected from {}", id, s.connection->peer());
            s.connection->start(
                [this, id](const proto::Header& h, proto::Message m) { onMessage(id, h, m); },
                [this, id](const std::string& reason) { onClose(id, reason); },
                [this, id](const proto::Header& h, std::vector<std::uint8_t> payload) {
                    auto it = sessions_.find(id);
                    if (it == sessions_.end() || ending_) return;
                    if (!it->second.ready)
                        return refuse(it->second, "a tile result before the scene was ready");
                    onTileResult(it->second, h, std::move(payload));
                });
            // First words: what this master runs, and a fresh nonce to prove the secret with.
            s.connection->send(
                proto::Challenge{proto::kVersion, IGI_BUILD_ID, key_.has_value(), s.nonce}, 0, 0);
        }
        accept();
    });
}

void Master::onMessage(ClientId id, const proto::Header& header, const proto::Message& message) {
    auto it = sessions_.find(id);
    if (it == sessions_.end() || ending_) return;
    Session& s = it->second;
    if (auto* hello = std::get_if<proto::Hello>(&message)) {
        onHello(s, *hello);
    } else if (auto* error = std::get_if<proto::Error>(&message)) {
        // Also before Hello: a client that refuses this master (another build) says why.
        spdlog::warn("client {} reports: {}", id, error->reason);
    } else if (!s.helloed) {
        refuse(s, "the first message must be Hello");
    } else if (auto* ready = std::get_if<proto::SceneReady>(&message)) {
        onSceneReady(s, *ready);
    } else if (!std::holds_alternative<proto::Heartbeat>(message)) {
        refuse(s,
               "unexpected " + proto::messageTypeName(proto::typeOf(message)) + " from a client");
    }
}

void Master::refuse(Session& s, const std::string& reason) {
    spdlog::warn("closing client {} ({}): {}", s.id, s.connection->peer(), reason);
    s.connection->send(proto::Error{reason}, 0, 0);
    s.connection->closeAfterSending(reason);
}

void Master::onHello(Session& s, const proto::Hello& hello) {
    if (s.helloed) return refuse(s, "a second Hello");
    if (hello.buildId != IGI_BUILD_ID)
        return refuse(
            s, "client build " + hello.buildId + " does not match master build " IGI_BUILD_ID);
    if (key_) {
        // Nothing is given to a peer that cannot prove it holds the cluster secret.
        if (!hello.proof ||
            !net::ClusterKey::same(*hello.proof, key_->clientProof(s.nonce, hello.nonce)))
            return refuse(s,
                          "authentication failed: the client does not hold this cluster's secret");
    }
    s.helloed = true;
    s.host = hello.hostname;
    s.threads = std::max(1u, hello.threads);
    ClientStats& c = stats_.client(s.id);
    c.host = hello.hostname;
    c.threads = hello.threads;
    std::optional<proto::AuthBytes> proof;
    if (key_) proof = key_->masterProof(s.nonce, hello.nonce);
    s.connection->send(proto::Welcome{s.id, scene_.render.seed, proof}, 0, 0);
    // The scene as loaded, plus the changes that bring it to now (through the history a GI mode
    // with lighting across epochs replays); then every update that follows.
    SceneTimeline::Join join = timeline_->join();
    sceneData_.changes = std::move(join.changes);
    sceneData_.baseFirstFrame = join.baseFirstFrame;
    sceneData_.history.clear();
    for (auto& e : join.history) sceneData_.history.push_back({e.firstFrame, std::move(e.changes)});
    if ((scene_.render.gi == GiMode::Spt || scene_.render.gi == GiMode::PhotonMap) &&
        !timeline_->historyComplete())
        spdlog::warn(
            "client {} joins at epoch {}, past the {} epochs of history a joiner replays: its "
            "photon groups start from epoch {}, so its tiles may be lit differently from the "
            "other clients' (docs/MODES.md)",
            s.id, timeline_->epoch(), proto::kMaxHistoryEpochs,
            timeline_->epoch() - sceneData_.history.size());
    s.connection->send(sceneData_, 0, timeline_->epoch());
    s.sceneSent = true;
}

void Master::onSceneReady(Session& s, const proto::SceneReady& ready) {
    if (s.ready) return refuse(s, "a second SceneReady");
    s.ready = true;
    s.lastResult = Clock::now();
    stats_.client(s.id).readySeconds = secondsSince(created_);
    spdlog::info("client {} ({}, {} threads) is ready: {} triangles built in {:.2f} s", s.id,
                 s.host, s.threads, ready.triangles, ready.buildSeconds);
    maybeStart();
    dispatch();
}

int Master::readyClients() const {
    return int(std::count_if(sessions_.begin(), sessions_.end(),
                             [](const auto& e) { return e.second.ready; }));
}

void Master::maybeStart() {
    if (started_ || readyClients() < std::max(1, options_.localClients + options_.remoteClients))
        return;
    started_ = true;
    renderStart_ = Clock::now();
    lastClientSeen_ = renderStart_;
    spdlog::info("{} clients ready after {:.2f} s: rendering {} frames", readyClients(),
                 secondsSince(created_), options_.frames);
}

void Master::openFramesAsNeeded() {
    // framesInFlight_ at most: the next one opens once every tile of the previous one has
    // been handed out, so clients never wait for the master to finish a frame.
    while (framesLeft(nextFrameToOpen_) &&
           nextFrameToOpen_ < nextFrameToFinish_ + framesInFlight_ &&
           (nextFrameToOpen_ == nextFrameToFinish_ ||
            scheduler_->frameFullyAssigned(nextFrameToOpen_ - 1))) {
        const std::uint32_t f = nextFrameToOpen_++;
        // A changed scene is a new epoch: every client gets the update before any tile of it
        // (one connection keeps the order), and keeps the old epoch for tiles still out.
        const SceneTimeline::FrameStart start = timeline_->beginFrame(f);
        if (!start.changes.empty()) {
            const proto::SceneUpdate update{start.changes};
            for (auto& [id, s] : sessions_)
                if (s.sceneSent) s.connection->send(update, f, start.epoch);
        }
        scheduler_->openFrame(f);
        auto record = std::make_unique<FrameRecord>();
        if (!spareBuffers_.empty()) {
            record->buffer = std::move(spareBuffers_.back());
            spareBuffers_.pop_back();
        }
        const RenderSettings& rs = scene_.render;
        record->buffer.reuse(scene_.image.width, scene_.image.height, rs.interleaveX,
                             rs.interleaveY, rs.tileSize);
        record->opened = Clock::now();
        record->epoch = start.epoch;
        // Accumulation restarts with every epoch (finishReadyFrames), so a frame's place in
        // it is known when it opens.
        if (openedEpoch_ != std::int64_t(start.epoch)) {
            openedEpoch_ = start.epoch;
            epochFirstFrame_ = f;
        }
        record->accumulation = scene_.render.accumulate ? f - epochFirstFrame_ : 0;
        frames_[f] = std::move(record);
    }
}

int Master::depthFor(const Session& s) const {
    // Enough tiles to cover ~20 ms of the client's work (latency hiding), and at least two per
    // eight threads so every core has chunks to take.
    const int byRate = int(std::ceil(s.tilesPerSecond * 0.02));
    return std::clamp(std::max(byRate + 1, 2 + int(s.threads) / 8), 2, 64);
}

void Master::dispatch() {
    if (!started_ || ending_) return;
    for (auto& [id, s] : sessions_) {
        if (!s.ready || !s.connection->isOpen()) continue;
        // A deep queue is refilled a quarter at a time rather than a tile per result: the
        // assignments then go out together, in one write (net::Connection gathers what is
        // queued), and one system call per tile was the master's largest cost with fast clients.
        const int depth = depthFor(s);
        if (scheduler_->inFlight(id) > depth - std::max(1, depth / 4)) continue;
        while (scheduler_->inFlight(id) < depth) {
            openFramesAsNeeded();
            const auto a = scheduler_->next(id, kDuplicateAfterSeconds);
            if (!a) break;
            const Tile& t = scheduler_->layout()[a->tile];
            stats_.noteAssignment(a->frame, id, t.setIndex(scene_.render.interleaveX));
            proto::TileAssign msg;
            msg.tileId = a->tile;
            msg.x0 = std::uint16_t(t.x0);
            msg.y0 = std::uint16_t(t.y0);
            msg.width = std::uint16_t(t.width);
            msg.height = std::uint16_t(t.height);
            msg.kx = std::uint16_t(t.kx);
            msg.ky = std::uint16_t(t.ky);
            const FrameRecord& record = *frames_.at(a->frame);
            msg.accumulation = record.accumulation;
            s.connection->send(msg, a->frame, record.epoch);
        }
    }
}

void Master::onTileResult(Session& s, const proto::Header& header,
                          std::vector<std::uint8_t> payload) {
    const auto& layout = scheduler_->layout();
    if (header.frame >= nextFrameToOpen_)
        return refuse(s, "a result for frame " + std::to_string(header.frame) +
                             ", which was never handed out");
    std::uint32_t tileId = 0;
    try {
        tileId = proto::peekTileId(payload);
    } catch (const proto::ProtocolError& e) {
        return refuse(s, std::string("protocol error: ") + e.what());
    }
    if (tileId >= layout.size())
        return refuse(s, "a result for tile " + std::to_string(tileId) + ", which does not exist");

    const auto now = Clock::now();
    const double age = std::chrono::duration<double>(now - s.lastResult).count();
    s.lastResult = now;
    s.tilesPerSecond = s.tilesPerSecond > 0 ? 0.8 * s.tilesPerSecond + 0.2 / std::max(age, 1e-4)
                                            : 1.0 / std::max(age, 1e-4);
    const std::uint64_t wireBytes = proto::kHeaderSize + header.payloadSize;
    // The first copy of a tile wins; a later copy is dropped before it costs any decoding.
    if (!scheduler_->complete(s.id, header.frame, tileId)) {
        stats_.addDuplicate(header.frame, s.id, wireBytes);
        return dispatch();
    }
    FrameRecord* record = frames_.at(header.frame).get();
    ++record->decoding;
    const Tile tile = layout[tileId];
    pool_.submit(
        [this, id = s.id, header, tileId, tile, record, wireBytes, payload = std::move(payload)] {
            const auto start = Clock::now();
            std::string error;
            proto::TileStats tileStats;
            try {
                // Decompressed and copied into the frame still quantized: the compositor
                // dequantizes the codes as it filters them (CodedFrame.h). A result refused
                // here has written nothing.
                const auto result = proto::decodeTileResultCodes(header, payload);
                record->buffer.scatter(tile, result.codes);  // checks the pixel count first
                tileStats = result.stats;
            } catch (const std::exception& e) {
                error = std::string("bad tile result: ") + e.what();
            }
            const double seconds = secondsSince(start);
            boost::asio::post(io_, [=, this] {
                onTileDecoded(id, header.frame, tileId, error, tileStats, wireBytes, seconds);
            });
        });
    dispatch();
}

void Master::onTileDecoded(ClientId id, std::uint32_t frame, std::uint32_t tile,
                           const std::string& error, const proto::TileStats& tileStats,
                           std::uint64_t wireBytes, double seconds) {
    FrameRecord& record = *frames_.at(frame);
    --record.decoding;
    record.decodeSeconds += seconds;
    if (!error.empty()) {
        // The tile goes to someone else; the client that sent garbage goes.
        scheduler_->reopen(frame, tile);
        auto it = sessions_.find(id);
        if (it != sessions_.end()) refuse(it->second, error);
        return dispatch();
    }
    const Tile& t = scheduler_->layout()[tile];
    stats_.addTile(
        frame, id, tileStats, wireBytes,
        std::uint32_t(t.pixelCount(scene_.render.interleaveX, scene_.render.interleaveY)));
    finishReadyFrames();
}

void Master::finishReadyFrames() {
    // Frames are composited one at a time, in order: accumulation adds them in sequence.
    if (compositing_ || ending_ || nextFrameToFinish_ >= nextFrameToOpen_) return;
    const std::uint32_t f = nextFrameToFinish_;
    FrameRecord* record = frames_.at(f).get();
    if (!scheduler_->frameDone(f) || record->decoding > 0) return;
    compositing_ = true;
    // Accumulation restarts when the scene changed, and goes on while it does not.
    const bool restart = compositedEpoch_ != std::int64_t(record->epoch);
    compositedEpoch_ = record->epoch;
    pool_.submit([this, f, record, restart] {
        const auto start = Clock::now();
        if (restart) compositor_->resetAccumulation();
        compositor_->composite(record->buffer);
        compositedUpTo_.store(f + 1);
        const double seconds = secondsSince(start);
        boost::asio::post(io_, [this, f, seconds] { onComposited(f, seconds); });
    });
}

void Master::noteShown(std::uint32_t f) {
    FrameStats& fs = stats_.frame(f);
    fs.epoch = frames_.at(f)->epoch;
    fs.accumulated = std::uint32_t(compositor_->accumulatedFrames());
    fs.shown = true;
}

void Master::onComposited(std::uint32_t f, double seconds) {
    compositing_ = false;
    FrameStats& fs = stats_.frame(f);
    fs.compositeSeconds = seconds;
    fs.decodeSeconds = frames_.at(f)->decodeSeconds;
    fs.seconds = secondsSince(frames_.at(f)->opened);
    noteShown(f);
    stats_.noteFrameDone(secondsSince(created_));
    // On a terminal the progress line says it; the frame lines are for logs and the curious.
    spdlog::log(progress_ ? spdlog::level::debug : spdlog::level::info, "{}",
                stats_.summaryLine(f));
    if (progress_) progress_->update(int(f + 1), stats_.recentFps(), readyClients());
    writeFrameImages(f);
    publishToView(f);
    scheduler_->closeFrame(f);
    timeline_->endFrame(f);
    spareBuffers_.push_back(std::move(frames_.at(f)->buffer));
    frames_.erase(f);
    ++nextFrameToFinish_;
    if (!framesLeft(nextFrameToFinish_)) {
        renderEnd_ = Clock::now();
        endSession(0);
        return;
    }
    finishReadyFrames();
    dispatch();
}

void Master::onClose(ClientId id, const std::string& reason) {
    auto it = sessions_.find(id);
    if (it == sessions_.end()) return;
    ClientStats& c = stats_.client(id);
    c.left = true;
    c.leaveReason = reason;
    c.leftSeconds = secondsSince(created_);
    const int released = started_ && !ending_ ? scheduler_->releaseClient(id) : 0;
    if (!ending_)
        spdlog::warn("client {} left ({}); {} of its tiles go to others", id, reason, released);
    sessions_.erase(it);
    if (ending_) {
        if (sessions_.empty()) io_.stop();
        return;
    }
    dispatch();
}

void Master::scheduleTick() {
    tick_.expires_after(kTickPeriod);
    tick_.async_wait([this](const boost::system::error_code& ec) {
        if (ec || ending_) return;
        // A connection that has not proved itself in time is dropped: a slot and a socket
        // are all an anonymous peer gets.
        for (auto& [id, s] : sessions_)
            if (!s.helloed && secondsSince(s.connected) > options_.handshakeSeconds &&
                s.connection->isOpen())
                refuse(s, "no valid Hello within " +
                              fmt::format("{:g}", options_.handshakeSeconds) + " s");
        if (!started_ && secondsSince(created_) > options_.waitSeconds) {
            spdlog::error("only {} of {} clients were ready after {:.0f} s", readyClients(),
                          std::max(1, options_.localClients + options_.remoteClients),
                          options_.waitSeconds);
            endSession(3);
            return;
        }
        // With every client gone, wait for new ones (they may be restarting) for as long as
        // for the first ones, then give up rather than hang.
        if (started_ && readyClients() > 0) lastClientSeen_ = Clock::now();
        if (started_ && secondsSince(lastClientSeen_) > options_.waitSeconds) {
            spdlog::error(
                "every client left and none came back within {:.0f} s; {} of {} frames done",
                options_.waitSeconds, nextFrameToFinish_, options_.frames);
            endSession(4);
            return;
        }
        // Heartbeats keep idle clients' read timeouts from firing; the tick also lets idle
        // clients pick up copies of tiles that have been out too long.
        if (++ticks_ % 50 == 0)
            for (auto& [id, s] : sessions_) s.connection->send(proto::Heartbeat{}, 0, 0);
        dispatch();
        scheduleTick();
    });
}

void Master::endSession(int exitCode) {
    if (ending_) return;
    ending_ = true;
    exitCode_ = exitCode;
    boost::system::error_code ignored;
    acceptor_.close(ignored);
    signals_.cancel(ignored);
    if (control_) control_->close();
    if (view_) view_->close();
    for (auto& snapshot : std::exchange(snapshots_, {}))
        snapshot.reply(
            nlohmann::json{{"ok", false}, {"error", "the session ended before the next frame"}}
                .dump());
    // Clients close on Shutdown; closing from this side could cut a client off while it still
    // writes a last result, which it would report as an error. Stragglers are closed after a
    // grace period.
    for (auto& [id, s] : sessions_) s.connection->send(proto::Shutdown{}, 0, 0);
    if (sessions_.empty()) {
        io_.stop();
        return;
    }
    tick_.expires_after(std::chrono::seconds(5));
    tick_.async_wait([this](const boost::system::error_code& ec) {
        if (ec) return;
        for (auto& [id, s] : sessions_) s.connection->close("session over");
    });
}

int Master::run() {
    try {
        loadScene();
        setUpSecret();
    } catch (const SceneError& e) {
        spdlog::error("{}", e.what());
        return 2;
    } catch (const std::invalid_argument& e) {
        spdlog::error("{}", e.what());
        return 2;
    }
    listen();
    if (options_.control) {
        control_ = std::make_unique<ControlServer>(
            io_, options_.controlHost, options_.controlPort,
            [this](const std::string& line, ControlServer::Reply reply) {
                onControl(line, std::move(reply));
            });
        spdlog::info("control commands on {}:{}", options_.controlHost, control_->port());
    }
    if (options_.view) startView();
    signals_.async_wait([this](const boost::system::error_code& ec, int signal) {
        if (ec) return;
        spdlog::warn("signal {}: ending the session after {} frames", signal, nextFrameToFinish_);
        renderEnd_ = Clock::now();
        endSession(0);
    });
    if (options_.localClients > 0) {
        const unsigned threads =
            options_.clientThreads > 0
                ? options_.clientThreads
                : std::max(1u, ThreadPool::defaultThreads() / unsigned(options_.localClients));
        const std::string port = std::to_string(acceptor_.local_endpoint().port());
        const std::string host =
            options_.listenHost == "0.0.0.0" ? "127.0.0.1" : options_.listenHost;
        std::vector<std::string> args = {"--connect",   host + ":" + port,
                                         "--threads",   std::to_string(threads),
                                         "--log-level", options_.clientLogLevel};
        if (options_.replayClients) args.push_back("--replay");
        // They belong to this session: when it ends or this master dies, they go too.
        args.insert(args.end(), {"--reconnect-seconds", "0"});
        std::vector<std::string> environment;
        if (options_.insecure) {
            args.push_back("--insecure");
        } else if (!localSecret_.empty()) {
            environment.push_back("IGI_SECRET=" + localSecret_);
        } else if (!options_.secretFile.empty()) {
            args.insert(args.end(), {"--secret-file", options_.secretFile.string()});
        }  // else: they inherit IGI_SECRET
        localClients_.start(LocalClients::clientExecutableBesideSelf(), args, options_.localClients,
                            environment);
    }
    scheduleTick();
    io_.run();
    pool_.waitIdle();  // a frame being composited or written, when the session was stopped
    // A frame composited after the session ended is in the image written below: report it as
    // shown, so that the image and the frame count agree.
    for (std::uint32_t f = nextFrameToFinish_; f < compositedUpTo_.load(); ++f) {
        noteShown(f);
        writeFrameImages(f);
        nextFrameToFinish_ = f + 1;
    }
    pool_.waitIdle();  // the sequence image just submitted
    localClients_.stop(10.0);
    if (progress_) progress_->finish();
    if (exitCode_ != 0) return exitCode_;

    const Image& image = compositor_->shown();
    for (const auto& path : options_.outputs) {
        writeImage(path, image, scene_.image.exposure);
        spdlog::info("wrote {}", path.string());
    }
    const double start = std::chrono::duration<double>(renderStart_ - created_).count();
    const double end = std::chrono::duration<double>(renderEnd_ - created_).count();
    spdlog::info("{} frames in {:.2f} s: {:.2f} fps", nextFrameToFinish_, end - start,
                 stats_.fps(end - start));
    if (!options_.statsJson.empty()) {
        stats_.writeJson(
            options_.statsJson,
            {{"scene", options_.scene.string()},
             {"width", std::to_string(scene_.image.width)},
             {"height", std::to_string(scene_.image.height)},
             {"integrator", scene_.render.integrator == IntegratorKind::Path ? "path" : "igi"}},
            start, end);
    }

    return 0;
}

}  // namespace igi

namespace igi {

void Master::writeFrameImages(std::uint32_t frame) {
    const auto& only = options_.sequenceFrames;
    const bool inSequence =
        !options_.outputSequence.empty() &&
        (only.empty() || std::find(only.begin(), only.end(), frame) != only.end());
    if (!inSequence && snapshots_.empty()) return;
    // The compositor's image changes with the next frame: write a copy, off the io thread.
    auto image = std::make_shared<Image>(compositor_->shown());
    const float exposure = scene_.image.exposure;
    if (inSequence) {
        pool_.submit([image, exposure, path = sequencePath(options_.outputSequence, frame)] {
            try {
                writeImage(path, *image, exposure);
            } catch (const std::exception& e) {
                spdlog::error("{}", e.what());
            }
        });
    }
    std::vector<Snapshot> due;
    std::erase_if(snapshots_, [&](Snapshot& s) {
        if (frame < s.fromFrame) return false;
        due.push_back(std::move(s));
        return true;
    });
    for (auto& [path, reply, fromFrame] : due) {
        pool_.submit([this, image, exposure, path, reply, frame] {
            nlohmann::json answer{{"ok", true}, {"path", path}, {"frame", frame}};
            try {
                writeImage(path, *image, exposure);
            } catch (const std::exception& e) {
                answer = {{"ok", false}, {"error", e.what()}};
            }
            boost::asio::post(io_, [reply, text = answer.dump()] { reply(text); });
        });
    }
}

void Master::onControl(const std::string& line, ControlServer::Reply reply) {
    auto error = [&](const std::string& what) {
        reply(nlohmann::json{{"ok", false}, {"error", what}}.dump());
    };
    ControlRequest request;
    try {
        request = parseControlCommand(line, scene_, timeline_->controlled());
    } catch (const std::exception& e) {
        return error(e.what());
    }
    switch (request.kind) {
        case ControlRequest::Kind::Change:
            try {
                timeline_->control(request.changes);
            } catch (const std::exception& e) {
                return error(e.what());
            }
            return reply(nlohmann::json{
                {"ok", true}, {"changes", request.changes.size()}, {"from_frame", nextFrameToOpen_}}
                             .dump());
        case ControlRequest::Kind::Status: {
            nlohmann::json status = statusJson();
            status["ok"] = true;
            return reply(status.dump());
        }
        case ControlRequest::Kind::Scene: {
            nlohmann::json scene = sceneJson();
            scene["ok"] = true;
            return reply(scene.dump());
        }
        case ControlRequest::Kind::Pick:
            return reply(pickJson(request.x, request.y).dump());
        case ControlRequest::Kind::Exposure:
            // Display only: the frames, their accumulation and the EXR outputs do not change.
            scene_.image.exposure = request.exposure;
            return reply(nlohmann::json{{"ok", true}, {"exposure", request.exposure}}.dump());
        case ControlRequest::Kind::Snapshot:
            if (request.path.empty()) request.path = defaultSnapshotPath();
            snapshots_.push_back({request.path, std::move(reply), nextFrameToOpen_});
            return;
        case ControlRequest::Kind::Stop:
            reply(nlohmann::json{{"ok", true}, {"frames_done", nextFrameToFinish_}}.dump());
            renderEnd_ = Clock::now();
            return endSession(0);
    }
}

}  // namespace igi

namespace igi {

std::uint32_t Master::maxTileResultBytes() const {
    int largest = 0;
    for (const Tile& t : scheduler_->layout())
        largest =
            std::max(largest, t.pixelCount(scene_.render.interleaveX, scene_.render.interleaveY));
    return std::uint32_t(4096 + 32 * std::size_t(largest));
}

void Master::setUpSecret() {
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

}  // namespace igi

namespace igi {
namespace {

nlohmann::json vec3Json(glm::vec3 v) {
    return nlohmann::json::array({v.x, v.y, v.z});
}

nlohmann::json cameraJson(const Camera& c) {
    return {{"position", vec3Json(c.position)},
            {"look_at", vec3Json(c.lookAt)},
            {"up", vec3Json(c.up)},
            {"fov_y", c.fovYDeg}};
}

// What a user reads to know which estimator runs: the mode and the settings that set its cost.
nlohmann::json settingsJson(const RenderSettings& s) {
    if (s.integrator == IntegratorKind::Path)
        return {{"integrator", "path"},
                {"samples_per_pixel", s.pathSamples},
                {"max_path_length", s.maxPathLength}};
    nlohmann::json j{{"integrator", "igi"},
                     {"gi", giModeName(s.gi)},
                     {"interleave", fmt::format("{}x{}", s.interleaveX, s.interleaveY)},
                     {"direct_samples", s.directSamples},
                     {"caustic_photons", s.causticPhotons},
                     {"accumulate", s.accumulate},
                     {"roulette", s.roulette}};
    if (s.gi == GiMode::Igi) j["indirect_vpls"] = s.indirectVpls;
    if (s.gi == GiMode::Spt) j["spt_groups"] = s.sptGroups, j["spt_budget"] = s.sptBudget;
    if (s.gi == GiMode::Stream)
        j["stream_vsls"] = s.streamVsls, j["stream_window"] = s.streamWindow;
    if (s.gi == GiMode::Cache)
        j["cache_spacing"] = s.cacheSpacing, j["cache_radius"] = s.cacheRadius;
    if (s.gi == GiMode::PhotonMap)
        j["photonmap_photons"] = s.photonmapGroups * s.photonmapPhotons,
        j["photonmap_caustics"] = s.photonmapScreenCaustics ? "screen" : "grid";
    return j;
}

}  // namespace

nlohmann::json Master::statusJson() {
    const Statistics::Rates& rates = stats_.sampleRates(secondsSince(created_));
    nlohmann::json clients = nlohmann::json::array();
    for (const auto& [id, s] : sessions_) {
        if (!s.ready) continue;
        const auto rays = rates.raysPerSecond.find(id);
        const auto tiles = rates.tilesPerSecond.find(id);
        clients.push_back(
            {{"id", id},
             {"host", s.host},
             {"address", s.connection->peer()},
             {"threads", s.threads},
             {"tiles_per_s", tiles == rates.tilesPerSecond.end() ? 0.0 : tiles->second},
             {"mrays_per_s", rays == rates.raysPerSecond.end() ? 0.0 : rays->second * 1e-6}});
    }
    return {{"frames_done", nextFrameToFinish_},
            {"frames_total", options_.frames},
            {"epoch", timeline_->epoch()},
            {"accumulated", compositor_->accumulatedFrames()},
            {"clients", readyClients()},
            {"client_list", clients},
            {"fps", stats_.recentFps()},
            {"wire_mb_per_s", rates.wireBytesPerSecond * 1e-6},
            {"camera", cameraJson(timeline_->controlled().camera)},
            {"exposure", scene_.image.exposure},
            {"width", scene_.image.width},
            {"height", scene_.image.height},
            {"settings", settingsJson(scene_.render)}};
}

nlohmann::json Master::sceneJson() const {
    const SceneState& state = timeline_->controlled();
    nlohmann::json objects = nlohmann::json::array();
    for (std::size_t m = 0; m < scene_.meshes.size(); ++m) {
        const Transform& t = state.transforms[m];
        objects.push_back({{"name", scene_.meshes[m].name},
                           {"translate", vec3Json(t.translate)},
                           {"rotate_deg", vec3Json(t.rotateDeg)},
                           {"scale", vec3Json(t.scale)}});
    }
    nlohmann::json lights = nlohmann::json::array();
    for (const QuadLight& l : state.quadLights)
        lights.push_back(
            {{"name", l.name}, {"type", "quad"}, {"on", l.on}, {"radiance", vec3Json(l.radiance)}});
    for (const PunctualLight& l : state.punctualLights) {
        const bool sun = l.kind == LightKind::Directional;
        nlohmann::json light = {{"name", l.name},
                                {"type", l.kind == LightKind::Point ? "point"
                                         : sun                      ? "directional"
                                                                    : "spot"},
                                {"on", l.on},
                                {sun ? "irradiance" : "intensity", vec3Json(l.intensity)}};
        if (l.kind != LightKind::Point) light["direction"] = vec3Json(l.direction);
        lights.push_back(std::move(light));
    }
    // The sky as the environment command sets it (the web view's sky sliders start from it).
    const nlohmann::json environment = {{"radiance", vec3Json(state.environment.radiance)},
                                        {"rotate_deg", state.environment.rotateDeg},
                                        {"map", state.environment.texture >= 0}};
    return {{"objects", objects},
            {"lights", lights},
            {"environment", environment},
            {"camera", cameraJson(state.camera)},
            {"exposure", scene_.image.exposure},
            {"width", scene_.image.width},
            {"height", scene_.image.height}};
}

nlohmann::json Master::pickJson(float x, float y) const {
    const SceneState& state = timeline_->controlled();
    const std::optional<PickHit> hit = pickObject(scene_, state, x, y);
    if (!hit) return {{"ok", true}, {"object", nullptr}};
    return {{"ok", true},
            {"object", scene_.meshes[hit->mesh].name},
            {"mesh", hit->mesh},
            {"point", vec3Json(hit->point)},
            {"distance", hit->distance},
            {"translate", vec3Json(state.transforms[hit->mesh].translate)}};
}

std::string Master::defaultSnapshotPath() {
    // Beside the first output, else in out/; numbered so that no snapshot replaces another.
    const std::filesystem::path dir = options_.outputs.empty()
                                          ? std::filesystem::path("out")
                                          : options_.outputs.front().parent_path();
    std::filesystem::path path;
    do {
        path = dir / fmt::format("snapshot_{:03d}.exr", ++snapshotsTaken_);
    } while (std::filesystem::exists(path));
    return path.string();
}

void Master::startView() {
    ViewServer::Options o;
    o.host = options_.viewHost;
    o.port = options_.viewPort;
    o.page = viewPage();
    // Off loopback whoever reaches the port could steer the session: a token, made now and
    // printed once, must then be in the URL of the page and of the WebSocket.
    const bool loopback = boost::asio::ip::make_address(o.host).is_loopback();
    if (!loopback) o.token = net::ClusterKey::randomSecret().substr(0, 32);
    const std::string token = o.token;
    view_ = std::make_unique<ViewServer>(
        io_, std::move(o), [this](const std::string& line, ControlServer::Reply reply) {
            onControl(line, std::move(reply));
        });
    if (loopback)
        spdlog::info("view on http://{}:{}/", options_.viewHost, view_->port());
    else
        spdlog::info(
            "view on http://{}:{}/?token={} (any address of this machine; the page and "
            "its WebSocket need the token)",
            options_.viewHost, view_->port(), token);
}

void Master::publishToView(std::uint32_t frame) {
    if (!view_ || view_->viewers() == 0) return;
    // Copied now: the compositor's image changes with the next frame.
    nlohmann::json status = statusJson();
    status["type"] = "frame";
    status["frame"] = frame;
    status["frame_epoch"] = stats_.frame(frame).epoch;
    status["frame_seconds"] = stats_.frame(frame).seconds;
    viewPending_ = ViewFrame{std::make_shared<const Image>(compositor_->shown()), status.dump(),
                             scene_.image.exposure};
    encodeViewFrame();
}

void Master::encodeViewFrame() {
    if (viewEncoding_ || !viewPending_) return;
    viewEncoding_ = true;
    pool_.submit([this, f = std::move(*viewPending_)] {
        std::shared_ptr<const std::string> message;
        try {
            message = ViewServer::frameMessage(f.status, encodeJpeg(*f.image, f.exposure));
        } catch (const std::exception& e) {
            spdlog::error("view: {}", e.what());
        }
        boost::asio::post(io_, [this, message] {
            viewEncoding_ = false;
            if (message && view_ && !ending_) view_->publish(message);
            encodeViewFrame();
        });
    });
    viewPending_.reset();
}

}  // namespace igi
