#pragma once

#include "image/Image.h"
#include "render/Accumulator.h"
#include "render/DiscontinuityFilter.h"
#include "render/FrameBuffer.h"
#include "render/RenderSettings.h"
#include "util/ThreadPool.h"

namespace igi {

/// Turns assembled frames into images on all the master's cores: the discontinuity buffer,
/// then accumulation of successive frames while nothing changes.
class FrameCompositor {
  public:
    FrameCompositor(int width, int height, const RenderSettings& settings, ThreadPool& pool);

    /// Filters `frame`, adds it to the accumulation (when enabled) and returns what to show:
    /// the running mean, or the frame itself without accumulation.
    const Image& composite(const FrameBuffer& frame);

    /// Starts a new accumulation (the view or the scene changed).
    void resetAccumulation();
    int accumulatedFrames() const { return accumulator_.frames(); }
    /// The last frame, filtered but not accumulated.
    const Image& lastFrame() const { return filtered_; }
    /// What composite() last returned: the accumulated mean, or the last frame.
    const Image& shown() const { return accumulate_ ? shown_ : filtered_; }

  private:
    template <typename F>
    void forRowBlocks(F&& f);

    int width_;
    int height_;
    bool accumulate_;
    DiscontinuityFilterSettings filter_;
    ThreadPool& pool_;
    Accumulator accumulator_;
    Image filtered_;
    Image unfiltered_;  ///< the frame without the buffer, for the progressive filter
    Image shown_;
};

}  // namespace igi
