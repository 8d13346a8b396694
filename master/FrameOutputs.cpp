#include "FrameOutputs.h"

#include <algorithm>
#include <filesystem>

#include <spdlog/spdlog.h>
#include <boost/asio/ip/address.hpp>
#include <boost/asio/post.hpp>

#include "OpenPort.h"
#include "SequencePath.h"
#include "ViewPage.h"
#include "image/ImageIO.h"
#include "image/JpegEncoder.h"
#include "net/ClusterKey.h"

namespace igi {

FrameOutputs::FrameOutputs(boost::asio::io_context& io, ThreadPool& pool,
                           const MasterOptions& options, const ImageSettings& image,
                           const FrameCompositor& compositor)
    : io_(io), pool_(pool), options_(options), image_(image), compositor_(compositor) {}

void FrameOutputs::writeFrameImages(std::uint32_t frame) {
    const auto& only = options_.sequenceFrames;
    const bool inSequence =
        !options_.outputSequence.empty() &&
        (only.empty() || std::find(only.begin(), only.end(), frame) != only.end());
    if (!inSequence && snapshots_.empty()) return;
    // The compositor's image changes with the next frame: write a copy, off the io thread.
    auto image = std::make_shared<Image>(compositor_.shown());
    const float exposure = image_.exposure;
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
                spdlog::info("snapshot of frame {} written to {}", frame, path);
            } catch (const std::exception& e) {
                answer = {{"ok", false}, {"error", e.what()}};
                spdlog::warn("snapshot of frame {} failed: {}", frame, e.what());
            }
            boost::asio::post(io_, [reply, text = answer.dump()] { reply(text); });
        });
    }
}

void FrameOutputs::snapshot(std::string path, ControlServer::Reply reply, std::uint32_t fromFrame) {
    if (path.empty()) path = defaultSnapshotPath();
    // Relative to the master's folder, which the one asking may not know: the reply and the
    // log give the whole path.
    path = std::filesystem::absolute(path).lexically_normal().string();
    snapshots_.push_back({std::move(path), std::move(reply), fromFrame});
}

std::string FrameOutputs::defaultSnapshotPath() {
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

void FrameOutputs::close() {
    closed_ = true;
    if (view_) view_->close();
    for (auto& snapshot : std::exchange(snapshots_, {}))
        snapshot.reply(
            nlohmann::json{{"ok", false}, {"error", "the session ended before the next frame"}}
                .dump());
}

bool FrameOutputs::writeOutputs() const {
    bool all = true;
    for (const auto& path : options_.outputs) {
        try {
            writeImage(path, compositor_.shown(), image_.exposure);
            spdlog::info("wrote {}", path.string());
        } catch (const std::exception& e) {
            spdlog::error("--output {}: {}", path.string(), e.what());
            all = false;
        }
    }
    if (!options_.errorOutput.empty()) {
        try {
            writeImage(options_.errorOutput, errorImage(), 0.0f);
            spdlog::info("wrote {}", options_.errorOutput.string());
        } catch (const std::exception& e) {
            spdlog::error("--error-output {}: {}", options_.errorOutput.string(), e.what());
            all = false;
        }
    }
    return all;
}

Image FrameOutputs::errorImage() const {
    const Image& shown = compositor_.shown();
    Image out(shown.width, shown.height);
    // Without accumulation (or before its third frame) there is no estimate: zeros.
    const std::vector<float>& error = compositor_.pixelRelMse();
    if (error.size() == out.pixels.size())
        for (std::size_t i = 0; i < error.size(); ++i) out.pixels[i] = glm::vec3(error[i]);
    return out;
}

void FrameOutputs::startView(ControlServer::Handler handler) {
    ViewServer::Options o;
    o.host = options_.viewHost;
    o.port = options_.viewPort;
    o.page = viewPage();
    // Off loopback whoever reaches the port could steer the session: a token, made now and
    // printed once, must then be in the URL of the page and of the WebSocket.
    const bool loopback = boost::asio::ip::make_address(o.host).is_loopback();
    if (!loopback) o.token = net::ClusterKey::randomSecret().substr(0, 32);
    const std::string token = o.token;
    view_ = openPort("--view", options_.viewHost, options_.viewPort, [&] {
        return std::make_unique<ViewServer>(io_, std::move(o), std::move(handler));
    });
    if (loopback)
        spdlog::info("view on http://{}:{}/", options_.viewHost, view_->port());
    else
        spdlog::info(
            "view on http://{}:{}/?token={} (any address of this machine; the page and "
            "its WebSocket need the token)",
            options_.viewHost, view_->port(), token);
}

void FrameOutputs::publishToView(const std::string& status) {
    if (!hasViewers()) return;
    // Copied now: the compositor's image changes with the next frame.
    viewPending_ =
        ViewFrame{std::make_shared<const Image>(compositor_.shown()), status, image_.exposure};
    encodeViewFrame();
}

void FrameOutputs::encodeViewFrame() {
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
            if (message && view_ && !closed_) view_->publish(message);
            encodeViewFrame();
        });
    });
    viewPending_.reset();
}

}  // namespace igi
