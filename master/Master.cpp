#include "Master.h"

#include <algorithm>

#include <spdlog/spdlog.h>
#include <boost/asio/post.hpp>

#include "Codec.h"
#include "JoinerScene.h"
#include "LocalClientLaunch.h"
#include "SessionScene.h"
#include "SettingsCommand.h"
#include "render/Tile.h"
#include "scene/RenderSettingsJson.h"
#include "scene/SceneError.h"

namespace igi {
namespace {

using Clock = std::chrono::steady_clock;

constexpr auto kTickPeriod = std::chrono::milliseconds(20);
// A tile is copied to an idle client only after it has been out at least this long (and three
// times its holder's usual latency, see TileScheduler): short enough to get past a stalled
// client, long enough not to duplicate every tile at the end of a frame.
constexpr double kDuplicateAfterSeconds = 0.05;
double secondsSince(Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
}

}  // namespace

Master::Master(MasterOptions options)
    : options_(std::move(options)),
      tick_(io_),
      pool_(options_.threads > 0 ? options_.threads : ThreadPool::defaultThreads()),
      signals_(io_, SIGINT, SIGTERM),
      nextFrameToOpen_(options_.firstFrame),
      nextFrameToFinish_(options_.firstFrame),
      created_(Clock::now()) {
    compositedUpTo_.store(options_.firstFrame);
    roster_ = std::make_unique<ClientRoster>(io_, options_, stats_,
                                             static_cast<ClientRoster::Events&>(*this), created_);
}

Master::~Master() = default;

void Master::loadScene() {
    SceneBundle bundle;
    scene_ = loadSessionScene(options_, bundle);
    sceneData_.bundle = std::move(bundle);
    sceneData_.settings = scene_.render;
    sceneData_.image = scene_.image;
    sceneData_.camera = scene_.camera;
    std::unique_ptr<Animation> animation;
    if (!options_.animation.empty()) {
        animation = std::make_unique<Animation>(Animation::load(options_.animation, scene_));
        options_.frames = framesWithAnimation(options_, *animation);
        if (!options_.framesGiven && progress_) progress_->setTotalFrames(options_.frames);
    }
    timeline_ =
        std::make_unique<SceneTimeline>(SceneState::of(scene_), std::move(animation),
                                        joinHistoryDepth(scene_.render), options_.firstFrame);

    const RenderSettings& s = scene_.render;
    makeFrames(s);
    compositor_ =
        std::make_unique<FrameCompositor>(scene_.image.width, scene_.image.height, s, pool_);
    spdlog::info("scene {}: {} meshes, {} materials, {}x{} pixels, {} tiles per frame, {}",
                 options_.scene.string(), scene_.meshes.size(), scene_.materials.size(),
                 scene_.image.width, scene_.image.height, scheduler_->layout().size(),
                 s.integrator == IntegratorKind::Path
                     ? fmt::format("path tracer, {} samples per pixel", s.pathSamples)
                     : fmt::format("IGI integrator, GI mode {}", giModeName(s.gi)));
}

void Master::makeFrames(const RenderSettings& s) {
    frameSettings_ = s;
    framesMadeAt_ = nextFrameToOpen_;
    auto layout = makeTiles(scene_.image.width, scene_.image.height, s.interleaveX, s.interleaveY,
                            s.tileSize);
    scheduler_ = std::make_unique<TileScheduler>(layout, s.setCount());
    frames_ = std::make_unique<OpenFrames>(scene_.image, s);
    adaptive_ = std::make_unique<AdaptiveTiles>(std::move(layout), scene_.image.width,
                                                scene_.image.height, s.interleaveX, s.interleaveY,
                                                s.tileSize, frames_->capacity());
}

bool Master::framesFollowSettings() {
    const RenderSettings& next = timeline_->controlled().render;
    if (sameFrameSettings(frameSettings_, next)) return true;
    // A settings command changed how frames are made: the frames in flight, made the old way,
    // are composited first; then the tile layout, the frame buffers and the compositor are made
    // anew, as a session started with the new settings at this frame makes them.
    if (nextFrameToOpen_ != nextFrameToFinish_ || compositing_) return false;
    pool_.waitIdle();  // the last frame's images may still be read from the compositor
    makeFrames(next);
    compositor_->reconfigure(next);
    spdlog::info("frame {}: tiles, filter and accumulation made anew for the new settings",
                 nextFrameToOpen_);
    return true;
}

void Master::onWelcomed(ConnectedClient& c) {
    // The scene as loaded, plus the changes that bring it to now; then every update that
    // follows.
    prepareJoinerScene(sceneData_, *timeline_, c.id);
    c.connection->send(sceneData_, 0, timeline_->epoch());
    c.sceneSent = true;
    const std::uint32_t oldestHeld = timeline_->oldestEpochAJoinerHolds();
    c.firstFrame = nextFrameToOpen_;
    for (std::uint32_t f = nextFrameToOpen_; f-- > nextFrameToFinish_;)
        if (frames_->at(f).epoch >= oldestHeld) c.firstFrame = f;
}

void Master::onReady(ConnectedClient& c, const proto::SceneReady& ready) {
    stats_.client(c.id).readySeconds = secondsSince(created_);
    spdlog::info("client {} ({}, {} threads) is ready: {} triangles built in {:.2f} s", c.id,
                 c.host, c.threads, ready.triangles, ready.buildSeconds);
    maybeStart();
    dispatch();
}

void Master::maybeStart() {
    if (limits_.started() ||
        roster_->readyCount() < std::max(1, options_.localClients + options_.remoteClients))
        return;
    limits_.start();
    lastClientSeen_ = limits_.startTime();
    spdlog::info("{} clients ready after {:.2f} s: rendering {} frames", roster_->readyCount(),
                 secondsSince(created_), options_.frames);
}

void Master::openFramesAsNeeded() {
    // OpenFrames::capacity at most: the next one opens once every tile of the previous one has
    // been handed out, so clients never wait for the master to finish a frame.
    while (limits_.frameLeft(nextFrameToOpen_) &&
           nextFrameToOpen_ < nextFrameToFinish_ + frames_->capacity() &&
           (nextFrameToOpen_ == nextFrameToFinish_ ||
            scheduler_->frameFullyAssigned(nextFrameToOpen_ - 1)) &&
           framesFollowSettings()) {
        const std::uint32_t f = nextFrameToOpen_++;
        // A changed scene is a new epoch: every client gets the update before any tile of it
        // (one connection keeps the order), and keeps the old epoch for tiles still out.
        const SceneTimeline::FrameStart start = timeline_->beginFrame(f);
        if (!start.changes.empty()) {
            // The statistics say from which frame a settings command's settings are in force.
            for (const SceneChange& change : start.changes)
                if (const auto* settings = std::get_if<SettingsChange>(&change))
                    stats_.frame(f).settings = renderSettingsJson(settings->settings).dump();
            const proto::SceneUpdate update{start.changes};
            for (auto& [id, c] : roster_->clients())
                if (c.sceneSent) c.connection->send(update, f, start.epoch);
        }
        // Adaptive tiles: the regions decided for this frame from the image composited as
        // it became openable, `capacity` frames before it (AdaptiveTiles), or all of them.
        TileRegions regions = adaptive_->regionsFor(f, start.epoch);
        if (regions.all()) {
            scheduler_->openFrame(f);
        } else {
            const std::vector<bool> leftOut = adaptive_->tilesLeftOut(regions);
            scheduler_->openFrame(f, &leftOut);
            stats_.frame(f).tilesLeftOut =
                std::uint32_t(std::count(leftOut.begin(), leftOut.end(), true));
        }
        frames_->open(f, start.epoch).rendered = std::move(regions);
    }
}

void Master::dispatch() {
    if (!limits_.started() || ending_) return;
    for (auto& [id, s] : roster_->clients()) {
        if (!s.ready || !s.connection->isOpen()) continue;
        // A deep queue is refilled a quarter at a time rather than a tile per result: the
        // assignments then go out together, in one write (net::Connection gathers what is
        // queued), and one system call per tile was the master's largest cost with fast clients.
        const int depth = s.queueDepth();
        if (scheduler_->inFlight(id) > depth - std::max(1, depth / 4)) continue;
        while (scheduler_->inFlight(id) < depth) {
            openFramesAsNeeded();
            const auto a = scheduler_->next(id, kDuplicateAfterSeconds, s.firstFrame);
            if (!a) break;
            const Tile& t = scheduler_->layout()[a->tile];
            stats_.noteAssignment(a->frame, id, t.setIndex(frameSettings_.interleaveX));
            s.connection->send(frames_->assignment(a->frame, a->tile, t), a->frame,
                               frames_->at(a->frame).epoch);
        }
    }
}

void Master::onTileResult(ConnectedClient& s, const proto::Header& header,
                          std::vector<std::uint8_t> payload) {
    if (ending_) return;
    const auto& layout = scheduler_->layout();
    if (header.frame >= nextFrameToOpen_)
        return roster_->refuse(s, "a result for frame " + std::to_string(header.frame) +
                                      ", which was never handed out");
    // A late copy of a tile of a frame made before the settings changed its layout: its tile
    // number is of the old layout.
    if (header.frame < framesMadeAt_) {
        stats_.addDuplicate(header.frame, s.id, proto::kHeaderSize + header.payloadSize);
        return dispatch();
    }
    std::uint32_t tileId = 0;
    try {
        tileId = proto::peekTileId(payload);
    } catch (const proto::ProtocolError& e) {
        return roster_->refuse(s, std::string("protocol error: ") + e.what());
    }
    if (tileId >= layout.size())
        return roster_->refuse(
            s, "a result for tile " + std::to_string(tileId) + ", which does not exist");

    s.noteResult(Clock::now());
    const std::uint64_t wireBytes = proto::kHeaderSize + header.payloadSize;
    // The first copy of a tile wins; a later copy is dropped before it costs any decoding.
    if (!scheduler_->complete(s.id, header.frame, tileId)) {
        stats_.addDuplicate(header.frame, s.id, wireBytes);
        return dispatch();
    }
    OpenFrames::Frame& record = frames_->at(header.frame);
    ++record.decoding;
    DecodedTile decoded;
    decoded.client = s.id;
    decoded.frame = header.frame;
    decoded.tile = tileId;
    decoded.wireBytes = wireBytes;
    decodeTileOnPool(pool_, io_, record, layout[tileId], header, std::move(payload), decoded,
                     [this](const DecodedTile& d) { onTileDecoded(d); });
    dispatch();
}

void Master::onTileDecoded(const DecodedTile& d) {
    OpenFrames::Frame& record = frames_->at(d.frame);
    --record.decoding;
    record.decodeSeconds += d.seconds;
    if (!d.error.empty()) {
        // The tile goes to someone else; the client that sent garbage goes.
        scheduler_->reopen(d.frame, d.tile);
        auto it = roster_->clients().find(d.client);
        if (it != roster_->clients().end()) roster_->refuse(it->second, d.error);
        return dispatch();
    }
    const Tile& t = scheduler_->layout()[d.tile];
    stats_.addTile(
        d.frame, d.client, d.stats, d.wireBytes,
        std::uint32_t(t.pixelCount(frameSettings_.interleaveX, frameSettings_.interleaveY)));
    finishReadyFrames();
}

void Master::finishReadyFrames() {
    // Frames are composited one at a time, in order: accumulation adds them in sequence.
    if (compositing_ || ending_ || nextFrameToFinish_ >= nextFrameToOpen_) return;
    const std::uint32_t f = nextFrameToFinish_;
    OpenFrames::Frame* record = &frames_->at(f);
    if (!scheduler_->frameDone(f) || record->decoding > 0) return;
    compositing_ = true;
    // Accumulation restarts when the scene changed, and goes on while it does not.
    const bool restart = compositedEpoch_ != std::int64_t(record->epoch);
    compositedEpoch_ = record->epoch;
    // What the next frame renders, if it renders this epoch: the cells of the regions it
    // leaves out are kept from this one.
    TileRegions next = adaptive_->regionsFor(f + 1, record->epoch);
    pool_.submit([this, f, record, restart, next = std::move(next)] {
        const auto start = Clock::now();
        if (restart) compositor_->resetAccumulation();
        adaptive_->prepareCells(record->buffer, record->rendered, next);
        compositor_->composite(record->buffer, &record->rendered);
        compositedUpTo_.store(f + 1);
        const double seconds = secondsSince(start);
        boost::asio::post(io_, [this, f, seconds] { onComposited(f, seconds); });
    });
}

void Master::noteShown(std::uint32_t f) {
    FrameStats& fs = stats_.frame(f);
    fs.epoch = frames_->at(f).epoch;
    fs.accumulated = std::uint32_t(compositor_->accumulatedFrames());
    fs.shown = true;
    limits_.shown().shown(int(fs.accumulated), *compositor_, adaptive_->regions(),
                          stats_.recentFps(), fs);
}

void Master::onComposited(std::uint32_t f, double seconds) {
    compositing_ = false;
    FrameStats& fs = stats_.frame(f);
    fs.compositeSeconds = seconds;
    fs.decodeSeconds = frames_->at(f).decodeSeconds;
    fs.seconds = secondsSince(frames_->at(f).opened);
    noteShown(f);
    // The regions of frame f + capacity, which may open now that this one is in
    // (AdaptiveTiles).
    if (options_.adaptiveTiles && frameSettings_.accumulate)
        adaptive_->decide(f, frames_->at(f).epoch, compositor_->accumulatedFrames(),
                          options_.targetError, limits_.shown().regionErrors());
    adaptive_->forgetBefore(f + 1);
    stats_.noteFrameDone(secondsSince(created_));
    // On a terminal the progress line says it; the frame lines are for logs and the curious.
    // A live session there has no progress line: a line a second, saying what it left out.
    const bool paced = options_.paceFrameLines && !progress_;
    const bool logged = !progress_ && (!paced || framePace_.due(secondsSince(created_)));
    spdlog::log(logged ? spdlog::level::info : spdlog::level::debug, "{}{}", stats_.summaryLine(f),
                paced && logged && framePace_.skippedBefore() > 0
                    ? fmt::format(" ({} frames since the last line)", framePace_.skippedBefore())
                    : "");
    if (progress_)
        progress_->update(int(f + 1 - options_.firstFrame), stats_.recentFps(),
                          roster_->readyCount(), limits_.shown().describe(stats_.recentFps()));
    outputs_->writeFrameImages(f);
    publishToView(f);
    stats_.closeFrame(f);
    scheduler_->closeFrame(f);
    timeline_->endFrame(f);
    frames_->close(f);
    ++nextFrameToFinish_;
    if (limits_.allFramesDone(framesDone())) {
        stop();
        return;
    }
    if (const std::string why = limits_.reached(framesDone()); !why.empty()) {
        endRendering(why);
        if (ending_) return;
    }
    finishReadyFrames();
    dispatch();
}

void Master::onLeft(ClientId id, const std::string& reason) {
    if (ending_) {
        if (roster_->empty()) io_.stop();
        return;
    }
    const int released = limits_.started() ? scheduler_->releaseClient(id) : 0;
    spdlog::warn("client {} left ({}); {} of its tiles go to others", id, reason, released);
    dispatch();
}

void Master::publishToView(std::uint32_t frame) {
    if (!outputs_->hasViewers()) return;
    nlohmann::json status = sessionControl_->statusJson();
    status["type"] = "frame";
    status["frame"] = frame;
    status["frame_epoch"] = stats_.frame(frame).epoch;
    status["frame_seconds"] = stats_.frame(frame).seconds;
    outputs_->publishToView(status.dump());
}

void Master::scheduleTick() {
    tick_.expires_after(kTickPeriod);
    tick_.async_wait([this](const boost::system::error_code& ec) {
        if (ec || ending_) return;
        roster_->dropSilentHandshakes();
        if (!limits_.started() && secondsSince(created_) > options_.waitSeconds) {
            spdlog::error("only {} of {} clients were ready after {:.0f} s", roster_->readyCount(),
                          std::max(1, options_.localClients + options_.remoteClients),
                          options_.waitSeconds);
            endSession(3);
            return;
        }
        // With every client gone, wait for new ones (they may be restarting) for as long as
        // for the first ones, then give up rather than hang.
        if (limits_.started() && roster_->readyCount() > 0) lastClientSeen_ = Clock::now();
        if (limits_.started() && secondsSince(lastClientSeen_) > options_.waitSeconds) {
            spdlog::error(
                "every client left and none came back within {:.0f} s; {} of {} frames done",
                options_.waitSeconds, framesDone(), options_.frames);
            endSession(4);
            return;
        }
        // Heartbeats keep idle clients' read timeouts from firing; the tick also lets idle
        // clients pick up copies of tiles that have been out too long.
        if (++ticks_ % 50 == 0) roster_->sendHeartbeats();
        stats_.noteTime(secondsSince(created_));  // igi-ctl status's rates
        // A time limit ends the rendering mid-frame too: the frames in flight are dropped.
        if (limits_.timeUp()) {
            endRendering(limits_.reached(framesDone()));
            if (ending_) return;
        }
        dispatch();
        scheduleTick();
    });
}

void Master::stop() {
    endSession(0);
}

void Master::endRendering(const std::string& why) {
    if (limits_.end(why)) stop();
}

void Master::setTargetError(double target) {
    options_.targetError = target;
    limits_.shown().setTarget(target);
}

void Master::resume(bool changed) {
    if (!limits_.resume(changed)) return;
    spdlog::info("rendering resumes at frame {}", nextFrameToOpen_);
    dispatch();
}

nlohmann::json Master::errorJson() const {
    return limits_.json(stats_.recentFps());
}

void Master::endSession(int exitCode) {
    if (ending_) return;
    ending_ = true;
    limits_.sessionEnds();
    exitCode_ = exitCode;
    boost::system::error_code ignored;
    signals_.cancel(ignored);
    if (sessionControl_) sessionControl_->closePorts();
    if (outputs_) outputs_->close();
    // Stragglers that do not close on Shutdown are closed after a grace period.
    if (!roster_ || roster_->shutDown()) {
        io_.stop();
        return;
    }
    tick_.expires_after(std::chrono::seconds(5));
    tick_.async_wait([this](const boost::system::error_code& ec) {
        if (!ec) roster_->closeAll("session over");
    });
}

int Master::run() {
    try {
        loadScene();
        roster_->setUpSecret();
    } catch (const SceneError& e) {
        spdlog::error("{}", e.what());
        return 2;
    } catch (const std::invalid_argument& e) {
        spdlog::error("{}", e.what());
        return 2;
    }
    outputs_ = std::make_unique<FrameOutputs>(io_, pool_, options_, scene_.image, *compositor_);
    sessionControl_ = std::make_unique<SessionControl>(static_cast<SessionControl::Frames&>(*this),
                                                       options_, scene_, *timeline_, stats_,
                                                       *roster_, *compositor_, *outputs_, created_);
    roster_->listen(scene_.render.seed, maxTileResultBytes());
    sessionControl_->openPorts(io_);
    signals_.async_wait([this](const boost::system::error_code& ec, int signal) {
        if (ec) return;
        spdlog::warn("signal {}: ending the session after {} frames", signal, framesDone());
        stop();
    });
    if (!options_.statsJson.empty()) {
        // Frames are written as they close: a session of days must not hold them all.
        try {
            stats_.streamFramesFor(options_.statsJson);
        } catch (const std::exception& e) {
            spdlog::error("{}", e.what());
            return 1;
        }
    }
    startLocalClients();
    scheduleTick();
    io_.run();
    pool_.waitIdle();  // a frame being composited or written, when the session was stopped
    // A frame composited after the session ended is in the image written below: report it as
    // shown, so that the image and the frame count agree.
    for (std::uint32_t f = nextFrameToFinish_; f < compositedUpTo_.load(); ++f) {
        noteShown(f);
        stats_.closeFrame(f);
        outputs_->writeFrameImages(f);
        nextFrameToFinish_ = f + 1;
    }
    pool_.waitIdle();  // the sequence image just submitted
    localClients_.stop(10.0);
    if (progress_) progress_->finish();
    if (exitCode_ != 0) return exitCode_;

    // One output that cannot be written (its disk full since the start) must not cost the
    // others theirs.
    const bool written = outputs_->writeOutputs();
    writeStatistics();
    return written ? 0 : 1;
}

void Master::startLocalClients() {
    if (options_.localClients <= 0) return;
    const LocalClientLaunch launch = localClientLaunch(
        options_, roster_->port(), roster_->localSecret(), ThreadPool::defaultThreads());
    // Under a progress line, the clients' own lines go above it, not into it.
    LocalClients::LineHandler onLine;
    if (progress_)
        onLine = [progress = progress_](const std::string& l) { progress->printAbove(l); };
    localClients_.start(LocalClients::clientExecutableBesideSelf(), launch.arguments,
                        options_.localClients, launch.environment, std::move(onLine));
}

void Master::writeStatistics() {
    const double start = std::chrono::duration<double>(limits_.startTime() - created_).count();
    const double end = std::chrono::duration<double>(limits_.endTime() - created_).count();
    spdlog::info("{} frames in {:.2f} s: {:.2f} fps", framesDone(), end - start,
                 stats_.fps(end - start));
    if (!options_.statsJson.empty())
        stats_.writeJson(options_.statsJson, sessionJson(options_, scene_), start, end);
}

std::uint32_t Master::maxTileResultBytes() const {
    // A tile holds at most tile_size x tile_size pixels of one cell, whatever the interleaving
    // (which a settings command may change; tile_size it may not).
    const std::size_t largest = std::size_t(std::min(scene_.render.tileSize, scene_.image.width)) *
                                std::size_t(std::min(scene_.render.tileSize, scene_.image.height));
    return std::uint32_t(4096 + 32 * largest);
}

}  // namespace igi
