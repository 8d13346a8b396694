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
    /// Before a frame's rows are added (one thread, none adding or reading): `partial` if it
    /// does not render every pixel (adaptive tiles). From the first partial frame on, each
    /// pixel counts the frames in its own sums, and its mean, variance and estimated error
    /// rest on its own count; until then, and for a session that never has one, the counts are
    /// the image's and the arithmetic is unchanged, bit for bit.
    void prepareFrame(bool partial);
    /// Adds row y of a frame (its filtered planes and, with withdrawBlur, its unfiltered ones)
    /// and writes the row's variance after it (varianceEntries() doubles, cell order).
    /// `rendered` (varianceEntries() floats, cell order; null: every pixel): 0 where the frame
    /// has no sample, whose sums and count then stay exactly as they were (the frame's values
    /// there are never read into them). Only after prepareFrame(true).
    void addRow(int y, const ShadedRow& row, double* variance, const float* rendered = nullptr,
                lanes::Isa isa = lanes::bestIsa());
    void endFrame() {
        firstHalf_ += inFirstHalf(frames_) ? 1 : 0;
        ++frames_;
    }
    /// Whether frame `frame` of an accumulation (0-based) goes to the first of the two halves
    /// meanRow's error estimate compares: the frames of the blocks [2^j, 2^(j+1)) with j odd
    /// (2-3, 8-15, 32-63, ...), the others (0-1, 4-7, 16-31, ...) to the second.
    /// Why blocks: a pixel's position in its footprint is one Sobol' sequence over the frames,
    /// and an aligned block of 2^j of its points is itself stratified (PixelSampler). A half
    /// made of such blocks is stratified as the whole is, only coarser (and holds as many even
    /// frames as odd ones), so at a pixel cut by an edge the estimate is 2.4x to 3.9x the true
    /// squared error of a pure edge from 8 to 256 frames (PixelSampler_test's model), where it
    /// was 2x to 19x with one frame of each pair in each half at random, each half a random
    /// pick of the points.
    /// Not even against odd frames: the even points of a Sobol' dimension lie in [0, 1/2) and
    /// the odd ones in [1/2, 1), so even and odd frames sample different halves of the domain
    /// and their means differ by a bias that no number of frames removes (measured: the
    /// estimate stopped falling at 9e-4 on CornellBox-Original while the true relMSE fell to
    /// 8e-5). The first half gets its first frame third: there is an estimate from
    /// kFirstEstimateFrames on.
    static bool inFirstHalf(int frame);
    /// The first accumulated frame count at which both halves have a frame (inFirstHalf), so
    /// that meanRow estimates an error: before it, the estimate is 0 and means nothing.
    static constexpr int kFirstEstimateFrames = 3;
    /// What addRow wrote for row y, given the sums after `frames` frames (with per-pixel
    /// counts, after each pixel's own).
    void varianceRow(int y, int frames, double* variance, lanes::Isa isa = lanes::bestIsa()) const;
    /// The mean of row y after `frames` frames, written to `out` (an image row, image order)
    /// with streamed stores: call streamedStoresDone() (CellOrder.h) before another thread reads
    /// it.
    /// `variance[k]`: the variance of row meanWindow(y).first + k (unused without withdrawBlur
    /// or before two frames).
    ///
    /// `error` (if not null, an image row of floats): each pixel's estimated relMSE, the
    /// expected (mean - truth)^2 / (truth^2 + 0.01) averaged over R, G, B, as igi-compare's
    /// relative_mse measures it against a reference (kRelativeMseEpsilon); 0 before
    /// kFirstEstimateFrames. Without a reference, from the frames' own spread: the sums of the
    /// first half's frames (inFirstHalf: blocks of frames, nA of the n) are kept beside those of
    /// all n, so the mean splits into two independent half-means, A of the first half and B of the
    /// others (nB = n - nA), with mean = (nA A + nB B) / n. If the frames are
    /// independent with variance s^2 each, Var(A) = s^2 / nA, Var(B) = s^2 / nB, and
    /// E[(A - B)^2] = s^2 (1 / nA + 1 / nB) = s^2 n / (nA nB), while Var(mean) = s^2 / n, so
    ///     Var(mean) = E[(A - B)^2] nA nB / n^2    (1/4 for nA = nB).
    /// With the progressive filter the mean shown is w F + (1 - w) U (F, U the filtered and
    /// unfiltered means); A and B are blended with the same w, so that their combination is
    /// still the mean shown exactly; and where w < 1 (the filter saw its blur) the blur is
    /// added: d = F - U holds the blur's bias and d's own noise, which the halves' d estimate
    /// as the mean's, so w^2 max(0, d^2 - (dA - dB)^2 nA nB / n^2) estimates the squared bias
    /// the blend keeps (high by chance where there is no blur: the pixels the filter withdraws
    /// by chance are those whose d is large). The relMSE's denominator stands for truth^2: it is
    /// max(0, A B), whose expectation is truth^2 (the halves are independent), where mean^2's
    /// is truth^2 + Var(mean): with mean^2, a pixel whose mean a rare bright frame raised
    /// divided its own large difference by its own large square (docs/ERROR_ESTIMATE.md has
    /// the figures). What
    /// this cannot see: a bias common to all frames (the blur the filter keeps where w = 1,
    /// the converged estimator's remaining bias), w's own dependence on the data, and a
    /// denominator that is still noisy where one half alone holds a bright frame (its A B grows
    /// with that frame, if only linearly). A bias of the first frame alone (the paper's clamp,
    /// which the converging estimator keeps in frame 0) is seen: it is in one half only, so
    /// (A - B)^2 nA nB / n^2 holds b^2 / n^2 times (other half's frames) / (its half's frames),
    /// about the mean's squared bias b^2 / n^2. One pixel's estimate rests on one difference (a
    /// chi-square of one degree of freedom): average it over pixels (a tile, the image) before
    /// deciding anything.
    void meanRow(int y, int frames, const double* const* variance, glm::vec3* out, float* error,
                 lanes::Isa isa = lanes::bestIsa()) const;
    /// The rows [first, second) whose variance the mean of row y reads.
    std::pair<int, int> meanWindow(int y) const;
    /// Entries of a variance row (the width, rounded up to whole lanes).
    std::size_t varianceEntries() const { return std::size_t(blocks_) * kPixelsPerBlock; }

    /// Frames added (partial ones included).
    int frames() const { return frames_; }
    /// The frames in pixel (x, y)'s sums: frames() unless some frame did not render it.
    double frameCount(int x, int y) const;
    /// Whether pixels count their own frames (a partial frame came since the last reset).
    bool countsPerPixel() const { return !counts_.empty(); }
    struct Layout;  ///< the kernels' view of the sums (RowAccumulator.cpp)
    bool withdrawsBlur() const { return withdrawBlur_; }

  private:
    static constexpr int kPixelsPerBlock = 8;

    CellOrder order_;
    int height_ = 0;
    int frames_ = 0;
    int firstHalf_ = 0;  ///< frames (of frames_) in the first half (inFirstHalf)
    bool withdrawBlur_ = false;
    int noiseX_ = 1;
    int noiseY_ = 1;
    int blocks_ = 0;  ///< blocks of kPixelsPerBlock pixels per row
    /// Sums per pixel: filtered RGB; with withdrawBlur unfiltered RGB and d^2; then those of
    /// the first half's frames (inFirstHalf), filtered RGB and (with withdrawBlur) unfiltered
    /// RGB (meanRow's error).
    int fields_ = 6;
    std::vector<double> sums_;
    /// Per pixel (cell order, varianceEntries() a row), once a frame was partial: the frames
    /// in its sums and, of them, the first half's. Doubles, as the kernels read them.
    std::vector<double> counts_;
    std::vector<double> firstHalfCounts_;
    /// Accumulator::blurTolerance(n) for every count a pixel can have.
    std::vector<double> tolerance_;

    Layout layout() const;
};

}  // namespace igi
