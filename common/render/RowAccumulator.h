#pragma once

#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "math/Lanes.h"
#include "render/CellOrder.h"
#include "render/RowFilter.h"

namespace igi {

/// Accumulator's running means, bit for bit the same arithmetic, for a compositor that works
/// row by row on rows in cell order (ShadedRow, RowFilter.h): eight pixels at a time, the sums
/// of eight pixels kept together (each sum of the eight, then the next sum), so that adding a
/// row and averaging it read one stream of memory. The per-pixel variance of the progressive
/// filter is not kept for the whole frame: adding a row hands it back, and the mean of a row
/// reads it only for the rows of its window (meanWindow), which the caller keeps meanwhile or
/// recomputes from the sums (varianceRow).
class RowAccumulator {
  public:
    /// As Accumulator::reset, for rows of `order`.
    void reset(const CellOrder& order, int height, bool withdrawBlur = false, int noiseX = 1,
               int noiseY = 1);
    /// Adds row y of a frame (its filtered planes and, with withdrawBlur, its unfiltered ones)
    /// and writes the row's variance after it (varianceEntries() doubles, cell order).
    void addRow(int y, const ShadedRow& row, double* variance, lanes::Isa isa = lanes::bestIsa());
    void endFrame() { ++frames_; }
    /// What addRow wrote for row y, given the sums after `frames` frames.
    void varianceRow(int y, int frames, double* variance, lanes::Isa isa = lanes::bestIsa()) const;
    /// The mean of row y after `frames` frames, written to `out` (an image row, image order)
    /// with streamed stores: call streamedStoresDone() (CellOrder.h) before another thread reads
    /// it.
    /// `variance[k]`: the variance of row meanWindow(y).first + k (unused without withdrawBlur
    /// or before two frames).
    void meanRow(int y, int frames, const double* const* variance, glm::vec3* out,
                 lanes::Isa isa = lanes::bestIsa()) const;
    /// The rows [first, second) whose variance the mean of row y reads.
    std::pair<int, int> meanWindow(int y) const;
    /// Entries of a variance row (the width, rounded up to whole lanes).
    std::size_t varianceEntries() const { return std::size_t(blocks_) * kPixelsPerBlock; }

    int frames() const { return frames_; }
    bool withdrawsBlur() const { return withdrawBlur_; }

  private:
    static constexpr int kPixelsPerBlock = 8;

    CellOrder order_;
    int height_ = 0;
    int frames_ = 0;
    bool withdrawBlur_ = false;
    int noiseX_ = 1;
    int noiseY_ = 1;
    int blocks_ = 0;  ///< blocks of kPixelsPerBlock pixels per row
    int fields_ = 3;  ///< sums per pixel: filtered RGB; with withdrawBlur unfiltered RGB and d^2
    std::vector<double> sums_;
};

}  // namespace igi
