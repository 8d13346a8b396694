#include "FrameCompositor.h"

#include <algorithm>

namespace igi {
namespace {

constexpr int kRowsPerBlock = 16;

bool withdrawBlur(const RenderSettings& s) {
    return s.accumulate && s.progressiveFilter;
}

}  // namespace

FrameCompositor::FrameCompositor(int width, int height, const RenderSettings& settings,
                                 ThreadPool& pool)
    : width_(width),
      height_(height),
      accumulate_(settings.accumulate),
      filter_{settings.effectiveFilterX(), settings.effectiveFilterY(),
              settings.filterDepthThreshold, settings.filterNormalThreshold},
      pool_(pool),
      filtered_(width, height),
      unfiltered_(withdrawBlur(settings) ? width : 0, withdrawBlur(settings) ? height : 0),
      shown_(width, height) {
    accumulator_.reset(width, height, withdrawBlur(settings), filter_.sizeX, filter_.sizeY);
}

template <typename F>
void FrameCompositor::forRowBlocks(F&& f) {
    const int blocks = (height_ + kRowsPerBlock - 1) / kRowsPerBlock;
    pool_.parallelFor(std::size_t(blocks), [&](std::size_t b) {
        const int begin = int(b) * kRowsPerBlock;
        f(begin, std::min(height_, begin + kRowsPerBlock));
    });
}

const Image& FrameCompositor::composite(const FrameBuffer& frame) {
    forRowBlocks([&](int begin, int end) {
        discontinuityFilterRows(frame, filter_, begin, end, filtered_.pixels);
    });
    if (!accumulate_) return filtered_;
    forRowBlocks([&](int begin, int end) {
        if (accumulator_.withdrawsBlur()) {
            compositeUnfilteredRows(frame, begin, end, unfiltered_.pixels);
            accumulator_.addRows(filtered_.pixels, unfiltered_.pixels, begin, end);
        } else {
            accumulator_.addRows(filtered_.pixels, begin, end);
        }
    });
    accumulator_.endFrame();
    forRowBlocks([&](int begin, int end) { accumulator_.meanRows(shown_.pixels, begin, end); });
    return shown_;
}

void FrameCompositor::resetAccumulation() {
    accumulator_.reset(width_, height_, accumulator_.withdrawsBlur(), filter_.sizeX, filter_.sizeY);
}

}  // namespace igi
