#include "FrameCompositor.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "render/RowFilter.h"

namespace igi {
namespace {

/// One block for one thread: nothing to balance, and no rows read across a block's edge
/// (decoded twice, averaged in a second sweep). Four a thread for more: enough to balance them,
/// few enough that those rows stay a small share.
int rowsPerBlock(int height, int threads) {
    const int blocks = threads > 1 ? 4 * threads : 1;
    return std::max(16, (height + blocks - 1) / blocks);
}

bool withdrawBlur(const RenderSettings& s) {
    return s.accumulate && s.progressiveFilter;
}

/// One thread's rows in flight: the frame rows the filter's window reads (row y in slot
/// y % size), the filtered row, and the variance rows the means read (the same way). Kept
/// from frame to frame, so that no frame allocates.
struct Workspace {
    std::vector<FrameRow> rows;
    ShadedRow shaded;
    std::vector<std::vector<double>> variance;
    std::vector<const double*> window;  ///< the variance rows of one mean
    std::vector<float> rendered;        ///< the row's pixels the frame renders (adaptive tiles)
};

/// The calling thread's workspace, with at least the rows asked for. It only grows: rings of
/// any size at least the window's hold each of its rows in a slot of its own.
Workspace& workspace(int filterRows, int noiseRows, std::size_t varianceEntries) {
    thread_local Workspace w;
    if (w.rows.size() < std::size_t(filterRows)) w.rows.resize(std::size_t(filterRows));
    for (FrameRow& r : w.rows) r.y = -1;  // a row of another frame is not this frame's
    if (w.variance.size() < std::size_t(noiseRows)) w.variance.resize(std::size_t(noiseRows));
    for (auto& v : w.variance) v.resize(varianceEntries);
    if (w.window.size() < std::size_t(noiseRows)) w.window.resize(std::size_t(noiseRows));
    w.rendered.resize(varianceEntries);
    return w;
}

}  // namespace

FrameCompositor::FrameCompositor(int width, int height, const RenderSettings& settings,
                                 ThreadPool& pool)
    : width_(width),
      height_(height),
      pool_(pool),
      rowsPerBlock_(rowsPerBlock(height, int(pool.size()))),
      filtered_(width, height) {
    reconfigure(settings);
}

void FrameCompositor::reconfigure(const RenderSettings& settings) {
    const DiscontinuityFilterSettings filter{
        settings.effectiveFilterX(), settings.effectiveFilterY(), settings.filterDepthThreshold,
        settings.filterNormalThreshold};
    if (filter.sizeY > FilterWindow::kMaxRows)
        throw std::invalid_argument("filter window taller than " +
                                    std::to_string(FilterWindow::kMaxRows) + " rows");
    filter_ = filter;
    accumulate_ = settings.accumulate;
    order_ = CellOrder(width_, settings.interleaveX);
    shown_ = Image(accumulate_ ? width_ : 0, accumulate_ ? height_ : 0);
    pixelError_.assign(accumulate_ ? std::size_t(width_) * height_ : 0, 0.0f);
    estimatedRelMse_ = 0.0;
    accumulator_.reset(order_, height_, withdrawBlur(settings), filter_.sizeX, filter_.sizeY);
}

template <typename F>
void FrameCompositor::forRowBlocks(F&& f) {
    const int blocks = (height_ + rowsPerBlock_ - 1) / rowsPerBlock_;
    pool_.parallelFor(std::size_t(blocks), [&](std::size_t b) {
        const int begin = int(b) * rowsPerBlock_;
        f(begin, std::min(height_, begin + rowsPerBlock_));
    });
}

const Image& FrameCompositor::composite(const proto::CodedFrame& frame,
                                        const TileRegions* rendered) {
    if (frame.width() != width_ || frame.height() != height_ ||
        frame.order().cells() != order_.cells())
        throw std::logic_error("a coded frame of another shape than the compositor's");
    return composite([&](int y, FrameRow& row) { frame.decodeRow(y, row); }, frame.live(kGlossy),
                     rendered);
}

const Image& FrameCompositor::composite(const FrameBuffer& frame, const TileRegions* rendered) {
    return composite([&](int y, FrameRow& row) { splitRow(frame, y, order_, row); },
                     frame.live.has(kGlossy), rendered);
}

const Image& FrameCompositor::composite(const RowSource& source, bool glossy,
                                        const TileRegions* rendered) {
    // Without accumulation a frame is shown as it is: adaptive tiles need the accumulation.
    const bool partial = accumulate_ && rendered && !rendered->all();
    if (accumulate_) accumulator_.prepareFrame(partial);
    // One sweep per block of rows: each row is filtered, added to the accumulation and, as
    // soon as the rows its mean reads are in, averaged, all while it is still in the cache.
    // A mean that reads a row of another block waits for the second sweep.
    const int after = accumulator_.frames() + 1;  // frames once this one is added
    const bool unfiltered = accumulate_ && accumulator_.withdrawsBlur();
    const int noiseRows = std::max(1, filter_.sizeY);
    forRowBlocks([&](int begin, int end) {
        Workspace& w =
            workspace(std::max(1, filter_.sizeY), noiseRows, accumulator_.varianceEntries());
        int next = begin;  // the first row whose mean is neither written nor left for later
        for (int y = begin; y < end; ++y) {
            FilterWindow window;
            const int y0 = filterWindowStart(y, filter_.sizeY, height_);
            window.count = std::min(height_, y0 + filter_.sizeY) - y0;
            for (int k = 0; k < window.count; ++k) {
                FrameRow& row = w.rows[std::size_t(y0 + k) % w.rows.size()];
                if (row.y != y0 + k) source(y0 + k, row);
                window.rows[k] = &row;
            }
            window.centre = &w.rows[std::size_t(y) % w.rows.size()];
            filterRow(window, order_, filter_, glossy, unfiltered, w.shaded);
            if (!accumulate_) {
                toImageOrder(order_, w.shaded[ShadedRow::kFr], w.shaded[ShadedRow::kFg],
                             w.shaded[ShadedRow::kFb],
                             filtered_.pixels.data() + std::size_t(y) * width_);
                continue;
            }
            const std::size_t entries = accumulator_.varianceEntries();
            if (partial)
                rendered->rowMask(y, order_, w.rendered.data(),
                                  entries - std::size_t(order_.width()));
            accumulator_.addRow(y, w.shaded, w.variance[std::size_t(y) % w.variance.size()].data(),
                                partial ? w.rendered.data() : nullptr);
            for (; next <= y; ++next) {
                const auto [first, last] = accumulator_.meanWindow(next);
                if (last > y + 1) break;  // reads rows not added yet
                if (first < begin) continue;
                for (int k = 0; k < last - first; ++k)
                    w.window[std::size_t(k)] =
                        w.variance[std::size_t(first + k) % w.variance.size()].data();
                accumulator_.meanRow(next, after, w.window.data(),
                                     shown_.pixels.data() + std::size_t(next) * width_,
                                     pixelError_.data() + std::size_t(next) * width_);
            }
        }
        streamedStoresDone();  // the means, before another thread reads them
    });
    if (!accumulate_) return filtered_;
    accumulator_.endFrame();
    forRowBlocks([&](int begin, int end) {
        Workspace* w = nullptr;
        for (int y = begin; y < end; ++y) {
            const auto [first, last] = accumulator_.meanWindow(y);
            if (first >= begin && last <= end) continue;
            if (!w) w = &workspace(1, noiseRows, accumulator_.varianceEntries());
            // The variance of rows of other blocks, from the sums: what adding them gave.
            for (int k = 0; k < last - first; ++k) {
                accumulator_.varianceRow(first + k, after, w->variance[std::size_t(k)].data());
                w->window[std::size_t(k)] = w->variance[std::size_t(k)].data();
            }
            accumulator_.meanRow(y, after, w->window.data(),
                                 shown_.pixels.data() + std::size_t(y) * width_,
                                 pixelError_.data() + std::size_t(y) * width_);
        }
        streamedStoresDone();
    });
    double sum = 0.0;
    for (const float e : pixelError_) sum += e;
    estimatedRelMse_ = pixelError_.empty() ? 0.0 : sum / double(pixelError_.size());
    return shown_;
}

double FrameCompositor::estimatedRelMse(const Tile& tile) const {
    double sum = 0.0;
    std::size_t count = 0;
    for (int y = tile.y0; y < std::min(height_, tile.y0 + tile.height); ++y)
        for (int x = tile.x0; x < std::min(width_, tile.x0 + tile.width); ++x) {
            sum += pixelError_[std::size_t(y) * width_ + x];
            ++count;
        }
    return count ? sum / double(count) : 0.0;
}

void FrameCompositor::resetAccumulation() {
    std::fill(pixelError_.begin(), pixelError_.end(), 0.0f);
    estimatedRelMse_ = 0.0;
    accumulator_.reset(order_, height_, accumulator_.withdrawsBlur(), filter_.sizeX, filter_.sizeY);
}

}  // namespace igi
