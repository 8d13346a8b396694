#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <nlohmann/json.hpp>

#include "ControlServer.h"
#include "FrameCompositor.h"
#include "MasterOptions.h"
#include "ViewServer.h"
#include "image/Image.h"
#include "scene/Scene.h"
#include "util/ThreadPool.h"

namespace igi {

/// Where composited images go: the sequence (--output-sequence), snapshots asked for by control
/// commands, the web view's browsers, and the outputs written at the end (--output). Images are
/// copied on the io thread (the compositor's image changes with the next frame) and written or
/// encoded on the pool.
class FrameOutputs {
  public:
    /// `image`: the scene's image settings (the exposure may change while the session runs).
    FrameOutputs(boost::asio::io_context& io, ThreadPool& pool, const MasterOptions& options,
                 const ImageSettings& image, const FrameCompositor& compositor);

    /// Serves the web view (docs/VIEW.md); its commands go to `handler`.
    void startView(ControlServer::Handler handler);
    bool hasViewers() const { return view_ && view_->viewers() > 0; }
    /// The compositor shows frame `frame`: writes its sequence image and the snapshots due.
    void writeFrameImages(std::uint32_t frame);
    /// The compositor's image goes to the view's browsers with `status` (a JSON object):
    /// tone-mapped and encoded on the pool, one frame at a time (frames composited meanwhile
    /// are skipped, not queued).
    void publishToView(const std::string& status);
    /// A snapshot of the first frame shown from `fromFrame` on (so that it shows every change
    /// commanded before it); an empty path numbers one beside the first output. Replies with
    /// the path written, or the error.
    void snapshot(std::string path, ControlServer::Reply reply, std::uint32_t fromFrame);
    /// The session ends: the view closes, snapshots still waiting are answered.
    void close();
    /// Writes the compositor's image to every --output, and its estimated relMSE per pixel to
    /// --error-output; one that fails (logged) does not stop the others. Returns whether all
    /// were written.
    bool writeOutputs() const;

  private:
    /// The estimated relMSE per pixel (FrameCompositor::pixelRelMse) as an image, R = G = B.
    Image errorImage() const;
    struct ViewFrame {
        std::shared_ptr<const Image> image;
        std::string status;
        float exposure = 0;
    };
    struct Snapshot {
        std::string path;
        ControlServer::Reply reply;
        std::uint32_t fromFrame = 0;
    };
    void encodeViewFrame();
    std::string defaultSnapshotPath();

    boost::asio::io_context& io_;
    ThreadPool& pool_;
    const MasterOptions& options_;
    const ImageSettings& image_;
    const FrameCompositor& compositor_;
    std::unique_ptr<ViewServer> view_;
    /// The newest composited image not yet encoded for the view, with its status.
    std::optional<ViewFrame> viewPending_;
    bool viewEncoding_ = false;
    bool closed_ = false;
    std::vector<Snapshot> snapshots_;
    int snapshotsTaken_ = 0;
};

}  // namespace igi
