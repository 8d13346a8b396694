#pragma once

#include <functional>

#include "CodedFrame.h"
#include "image/Image.h"
#include "render/CellOrder.h"
#include "render/DiscontinuityFilter.h"
#include "render/FrameBuffer.h"
#include "render/FrameRow.h"
#include "render/RenderSettings.h"
#include "render/RowAccumulator.h"
#include "render/Tile.h"
#include "render/TileRegions.h"
#include "util/ThreadPool.h"

namespace igi {

/// Turns assembled frames into images on all the master's cores: the discontinuity buffer,
/// then accumulation of successive frames while nothing changes. The results are bit for bit
/// those of discontinuityFilterRows and Accumulator (the reference, one pass after the other),
/// in one sweep over each block of rows: a row is dequantized, filtered, added and averaged
/// while it is in the cache, eight pixels at a time.
class FrameCompositor {
  public:
    FrameCompositor(int width, int height, const RenderSettings& settings, ThreadPool& pool);

    /// Filters `frame`, adds it to the accumulation (when enabled) and returns what to show:
    /// the running mean, or the frame itself without accumulation. The frame's cells must be
    /// the settings' interleaving. `rendered` (null: all): the regions the frame rendered
    /// (adaptive tiles); the frame must hold cells in the others too, which the discontinuity
    /// buffer reads for the pixels beside them, but they are not accumulated: those pixels
    /// keep their mean and count (RowAccumulator::prepareFrame).
    const Image& composite(const proto::CodedFrame& frame, const TileRegions* rendered = nullptr);
    /// The same for a frame of floats (tests, tools).
    const Image& composite(const FrameBuffer& frame, const TileRegions* rendered = nullptr);

    /// Starts a new accumulation (the view or the scene changed).
    void resetAccumulation();
    /// Composites frames of `settings` from now on (interleave, filter, accumulate: a settings
    /// command's), as a compositor made with them would; the accumulation starts anew. Not
    /// while a frame is being composited or an image read.
    void reconfigure(const RenderSettings& settings);
    int accumulatedFrames() const { return accumulator_.frames(); }
    /// The frames in pixel (x, y)'s mean (fewer than accumulatedFrames() where adaptive tiles
    /// left it out).
    double pixelFrames(int x, int y) const { return accumulator_.frameCount(x, y); }
    /// What composite() last returned: the accumulated mean, or the last frame.
    const Image& shown() const { return accumulate_ ? shown_ : filtered_; }
    /// The accumulated mean's relMSE as estimated from the frames' spread, without a reference
    /// (RowAccumulator::meanRow derives it): the mean over the image's pixels. 0 before two
    /// frames are in, and without accumulation.
    double estimatedRelMse() const { return estimatedRelMse_; }
    /// The same over the pixels of the region of `tile` (all its cells: what one tile of every
    /// set renders).
    double estimatedRelMse(const Tile& tile) const;
    /// Each pixel's estimate (row-major; empty without accumulation). One pixel's rests on one
    /// difference of two half-means: average it over a region before trusting it.
    const std::vector<float>& pixelRelMse() const { return pixelError_; }

  private:
    /// Fills `row` with row y of the frame being composited (in order_).
    using RowSource = std::function<void(int y, FrameRow& row)>;
    const Image& composite(const RowSource& rows, bool glossy, const TileRegions* rendered);
    template <typename F>
    void forRowBlocks(F&& f);

    int width_;
    int height_;
    bool accumulate_;
    DiscontinuityFilterSettings filter_;
    ThreadPool& pool_;
    CellOrder order_;
    int rowsPerBlock_;
    RowAccumulator accumulator_;
    Image filtered_;  ///< the last frame, filtered: what is shown without accumulation
    Image shown_;
    std::vector<float> pixelError_;  ///< estimated relMSE per pixel (accumulating)
    double estimatedRelMse_ = 0.0;
};

}  // namespace igi
