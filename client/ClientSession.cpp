#include "ClientSession.h"

#include <chrono>
#include <thread>

#include <spdlog/spdlog.h>
#include <boost/asio/connect.hpp>
#include <boost/asio/ip/host_name.hpp>
#include <boost/asio/ip/tcp.hpp>

#include "render/Tile.h"
#include "scene/SceneError.h"
#include "scene/SceneLoader.h"

namespace igi {
namespace {

constexpr auto kHeartbeatPeriod = std::chrono::seconds(2);

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
    if (!connect()) return 2;
    spdlog::info("connected to the master at {}", connection_->peer());
    connection_->start(
        [this](const proto::Header& h, proto::Message m) { onMessage(h, std::move(m)); },
        [this](const std::string& reason) { onClose(reason); });
    proto::Hello hello;
    hello.buildId = IGI_BUILD_ID;
    hello.threads = pool_.size();
    hello.hostname = boost::asio::ip::host_name();
    connection_->send(hello, 0, 0);
    scheduleHeartbeat();
    io_.run();
    return exitCode_;
}

void ClientSession::scheduleHeartbeat() {
    heartbeat_.expires_after(kHeartbeatPeriod);
    heartbeat_.async_wait([this](const boost::system::error_code& ec) {
        if (ec || !connection_->isOpen()) return;
        connection_->send(proto::Heartbeat{}, 0, 0);
        scheduleHeartbeat();
    });
}

void ClientSession::onMessage(const proto::Header& header, proto::Message message) {
    if (auto* welcome = std::get_if<proto::Welcome>(&message)) {
        spdlog::info("the master calls this client {}", welcome->clientId);
    } else if (auto* data = std::get_if<proto::SceneData>(&message)) {
        onSceneData(std::move(*data));
    } else if (auto* tile = std::get_if<proto::TileAssign>(&message)) {
        onTile(header, *tile);
    } else if (std::holds_alternative<proto::Shutdown>(message)) {
        spdlog::info("the master ended the session");
        exitCode_ = 0;
        connection_->close("shutdown");
    } else if (auto* error = std::get_if<proto::Error>(&message)) {
        spdlog::error("the master refused this client: {}", error->reason);
        connection_->close("error from the master");
    } else if (!std::holds_alternative<proto::Heartbeat>(message)) {
        connection_->close("unexpected " + proto::messageTypeName(proto::typeOf(message)) +
                           " from the master");
    }
}

void ClientSession::onClose(const std::string& reason) {
    if (exitCode_ != 0) spdlog::error("connection to the master closed: {}", reason);
    heartbeat_.cancel();
    pool_.clearPending();  // tiles nobody will receive
    io_.stop();
}

void ClientSession::onSceneData(proto::SceneData data) {
    if (ready_) {
        connection_->close("a second scene in one session");
        return;
    }
    // Building can take a while for big scenes: do it off the io thread, so heartbeats go on.
    pool_.submit([this, data = std::move(data)]() mutable {
        try {
            const auto start = std::chrono::steady_clock::now();
            scene_ = std::make_unique<Scene>(loadSceneBundle(data.bundle));
            scene_->render = data.settings;
            scene_->image = data.image;
            scene_->camera = data.camera;
            traceable_ = std::make_unique<TraceableScene>(device_, *scene_);
            renderer_ = std::make_unique<TileRenderer>(*traceable_, *scene_, scene_->render,
                                                       scene_->camera, scene_->image);
            const float seconds =
                std::chrono::duration<float>(std::chrono::steady_clock::now() - start).count();
            spdlog::info(
                "scene '{}' ready: {} triangles in {:.2f} s, {} light paths and {} direct samples "
                "per set{}",
                data.bundle.sceneName, traceable_->triangleCount(), seconds,
                renderer_->builder().vplPaths(), scene_->render.directSamples,
                renderer_->builder().causticsActive() ? ", caustics on" : "");
            ready_ = true;
            connection_->send(proto::SceneReady{traceable_->triangleCount(), seconds}, 0, 0);
        } catch (const std::exception& e) {
            spdlog::error("cannot build the scene: {}", e.what());
            connection_->send(proto::Error{std::string("cannot build the scene: ") + e.what()}, 0,
                              0);
            connection_->closeAfterSending("scene build failed");
        }
    });
}

void ClientSession::onTile(const proto::Header& header, const proto::TileAssign& a) {
    if (!ready_) {
        connection_->close("a tile before the scene was ready");
        return;
    }
    const RenderSettings& s = scene_->render;
    const Tile tile{a.x0, a.y0, a.width, a.height, a.kx, a.ky};
    if (a.kx >= s.interleaveX || a.ky >= s.interleaveY || a.x0 % s.interleaveX != 0 ||
        a.y0 % s.interleaveY != 0 || a.x0 + a.width > scene_->image.width ||
        a.y0 + a.height > scene_->image.height) {
        connection_->close("a tile outside the image or the interleaving pattern");
        return;
    }
    if (header.frame > newestFrame_) {
        newestFrame_ = header.frame;
        // Sets of frames two behind are no longer needed: frames are pipelined one deep.
        if (newestFrame_ >= 2) renderer_->cache().evictBefore(newestFrame_ - 1);
    }
    const std::uint32_t frame = header.frame, epoch = header.epoch;
    if (options_.replay) return replayTile(frame, epoch, a.tileId, tile);

    renderer_->render(pool_, frame, a.tileId, tile,
                      [this, frame, epoch](proto::TileResult&& result) {
                          connection_->send(result, frame, epoch);
                      });
}

}  // namespace igi

namespace igi {

void ClientSession::replayTile(std::uint32_t frame, std::uint32_t epoch, std::uint32_t tileId,
                               const Tile& tile) {
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
    renderer_->render(
        pool_, frame, tileId, tile, [this, frame, epoch, tileId](proto::TileResult&& result) {
            std::vector<std::uint8_t> bytes = proto::encodeMessage(result, frame, epoch);
            {
                std::lock_guard lock(replayMutex_);
                recorded_[tileId] = bytes;
            }
            connection_->sendEncoded(std::move(bytes));
        });
}

}  // namespace igi
