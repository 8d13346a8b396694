#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include "CodedFrame.h"
#include "Messages.h"
#include "render/Tile.h"
#include "render/TileRegions.h"
#include "scene/Scene.h"

namespace igi {

/// The frames open at once, each with the buffer its tile results are decoded into, its epoch
/// and its place in the accumulation. Bounds how many are open (pipelining against memory) and
/// reuses the buffers of closed frames.
class OpenFrames {
  public:
    struct Frame {
        proto::CodedFrame buffer;
        std::chrono::steady_clock::time_point opened;
        std::uint32_t epoch = 0;  ///< the scene state every tile of it renders
        /// Its place in the accumulation (TileAssign::accumulation): frames since its epoch
        /// began, or 0 without accumulation.
        std::uint32_t accumulation = 0;
        int decoding = 0;          ///< tile results being decoded on the pool
        double decodeSeconds = 0;  ///< pool time spent decoding and scattering its tiles
        /// The tile regions it renders (AdaptiveTiles; every one unless a target leaves some
        /// out).
        TileRegions rendered;
    };

    /// For images of `image`'s size laid out in tiles by `render`.
    OpenFrames(const ImageSettings& image, const RenderSettings& render);

    /// How many frames may be open at once (from the image size).
    std::uint32_t capacity() const { return capacity_; }
    /// Opens frame `frame` of scene epoch `epoch`; frames open in order. The reference stays
    /// valid until the frame is closed.
    Frame& open(std::uint32_t frame, std::uint32_t epoch);
    Frame& at(std::uint32_t frame) { return *frames_.at(frame); }
    /// The message that hands tile `tileId` (`tile`) of open frame `frame` to a client.
    proto::TileAssign assignment(std::uint32_t frame, std::uint32_t tileId, const Tile& tile);
    /// Closes `frame`, keeping its buffer for a frame to come.
    void close(std::uint32_t frame);

  private:
    ImageSettings image_;
    int interleaveX_, interleaveY_, tileSize_;
    bool accumulate_;
    std::uint32_t capacity_;
    std::map<std::uint32_t, std::unique_ptr<Frame>> frames_;
    /// Buffers of closed frames: a fresh one would cost the master its page faults and
    /// clearing every frame (CodedFrame::reuse).
    std::vector<proto::CodedFrame> spare_;
    std::int64_t openedEpoch_ = -1;      ///< epoch of the frame last opened
    std::uint32_t epochFirstFrame_ = 0;  ///< the first frame of openedEpoch_
};

}  // namespace igi
