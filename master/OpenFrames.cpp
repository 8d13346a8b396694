#include "OpenFrames.h"

#include <algorithm>

namespace igi {
namespace {

// Frames open at once. A frame's last tiles wait on its slowest holders; while they do, the
// other clients work on the next frames. With two, 16 clients each capped to a sixteenth of a
// core idled in every frame's tail and reached 60-70 % of linear scaling; with four, linear
// (scripts/bench_performance.sh, docs/PERFORMANCE.md).
constexpr std::uint32_t kFramesInFlight = 4;
// Each open frame holds a full-size CodedFrame: big images open fewer frames (never fewer
// than two, which pipelining needs) to keep these buffers within this budget.
constexpr std::size_t kOpenFrameBufferBudget = std::size_t{1} << 30;

}  // namespace

OpenFrames::OpenFrames(const ImageSettings& image, const RenderSettings& render)
    : image_(image),
      interleaveX_(render.interleaveX),
      interleaveY_(render.interleaveY),
      tileSize_(render.tileSize),
      accumulate_(render.accumulate) {
    const std::size_t frameBytes =
        proto::CodedFrame::kBytesPerPixel * std::size_t(image.width) * std::size_t(image.height);
    capacity_ = std::uint32_t(
        std::clamp<std::size_t>(kOpenFrameBufferBudget / frameBytes, 2, kFramesInFlight));
}

OpenFrames::Frame& OpenFrames::open(std::uint32_t frame, std::uint32_t epoch) {
    auto record = std::make_unique<Frame>();
    if (!spare_.empty()) {
        record->buffer = std::move(spare_.back());
        spare_.pop_back();
    }
    record->buffer.reuse(image_.width, image_.height, interleaveX_, interleaveY_, tileSize_);
    record->opened = std::chrono::steady_clock::now();
    record->epoch = epoch;
    // Accumulation restarts with every epoch (the master's compositing), so a frame's place in
    // it is known when it opens.
    if (openedEpoch_ != std::int64_t(epoch)) {
        openedEpoch_ = epoch;
        epochFirstFrame_ = frame;
    }
    record->accumulation = accumulate_ ? frame - epochFirstFrame_ : 0;
    Frame& opened = *record;
    frames_[frame] = std::move(record);
    return opened;
}

proto::TileAssign OpenFrames::assignment(std::uint32_t frame, std::uint32_t tileId,
                                         const Tile& tile) {
    proto::TileAssign message;
    message.tileId = tileId;
    message.x0 = std::uint16_t(tile.x0);
    message.y0 = std::uint16_t(tile.y0);
    message.width = std::uint16_t(tile.width);
    message.height = std::uint16_t(tile.height);
    message.kx = std::uint16_t(tile.kx);
    message.ky = std::uint16_t(tile.ky);
    message.accumulation = at(frame).accumulation;
    return message;
}

void OpenFrames::close(std::uint32_t frame) {
    auto it = frames_.find(frame);
    if (it == frames_.end()) return;
    spare_.push_back(std::move(it->second->buffer));
    frames_.erase(it);
}

}  // namespace igi
