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
    // One sweep per block of rows: each row is filtered, added to the accumulation and, as
    // soon as the rows its mean reads are in, averaged, all while it is still in the cache.
    // A mean that reads a row of another block waits for the second sweep.
    const int after = accumulator_.frames() + 1;  // frames once this one is added
    forRowBlocks([&](int begin, int end) {
        DiscontinuityRowFilter filter(frame, filter_);
        int next = begin;  // the first row whose mean is neither written nor left for later
        for (int y = begin; y < end; ++y) {
            filter.filterRow(y, filtered_.pixels);
            if (!accumulate_) continue;
            if (accumulator_.withdrawsBlur()) {
                compositeUnfilteredRows(frame, y, y + 1, unfiltered_.pixels);
                accumulator_.addRows(filtered_.pixels, unfiltered_.pixels, y, y + 1);
            } else {
                accumulator_.addRows(filtered_.pixels, y, y + 1);
            }
            for (; next <= y; ++next) {
                const auto [first, last] = accumulator_.meanWindow(next);
                if (last > y + 1) break;  // reads rows not added yet
                if (first >= begin) accumulator_.meanRows(shown_.pixels, next, next + 1, after);
            }
        }
    });
    if (!accumulate_) return filtered_;
    accumulator_.endFrame();
    forRowBlocks([&](int begin, int end) {
        for (int y = begin; y < end; ++y) {
            const auto [first, last] = accumulator_.meanWindow(y);
            if (first < begin || last > end) accumulator_.meanRows(shown_.pixels, y, y + 1);
        }
    });
    return shown_;
}

void FrameCompositor::resetAccumulation() {
    accumulator_.reset(width_, height_, accumulator_.withdrawsBlur(), filter_.sizeX, filter_.sizeY);
}

}  // namespace igi
