#pragma once

#include <utility>
#include <vector>

#include <glm/vec3.hpp>

namespace igi {

/// Averages successive frames while nothing changes, so a still view converges (the
/// accumulation buffer of the paper). Sums are kept in double so that thousands of frames
/// lose no precision.
///
/// With `withdrawBlur`, each frame comes twice, through the discontinuity buffer and without
/// it, and the mean shown is, pixel by pixel, a blend of the two means: the filtered one where
/// the frames give no evidence that the filter's blur moves the pixel (every pixel of a smooth
/// surface, and every pixel while few frames are in), the unfiltered one in proportion as they
/// do. The buffer averages a pixel with its neighbours, which takes the interleaving's
/// structured noise away but also blurs what changes across them (contact shadows, creases,
/// the edges of caustics); that blur does not average out, so without this the accumulated
/// image would converge to a blurred image instead of the true one. Per pixel, with D the
/// difference of the two means' luminances and s^2 the variance of that difference (from the
/// frames' own differences), the weight of the filtered mean is 1 if D^2 <= k s^2 and
/// k s^2 / D^2 otherwise (k = blurTolerance(frames)): as frames come in s^2 falls like 1 / frames,
/// so where the blur has a bias b the weight falls like 1 / (b^2 frames) and the mean converges to
/// the unfiltered, unbiased one; where it has none, D stays within its noise and the filtered mean
/// (with about a ninth of the variance) stays.
///
/// s^2 is pooled over a window (the discontinuity buffer's, so that it holds every interleaving
/// cell): the larger of the pixel's own estimate and the window's mean. IGI's noise is heavy-tailed
/// (a VPL close to a glossy surface is a rare, large term), and a pixel whose light sets have not
/// drawn such a term yet has a small sample variance: judged alone, its lower unfiltered mean
/// looks significant and the blur is withdrawn there, which leaves dark dots in the lattice of
/// the interleaving cells (all pixels of a cell share a set). Its neighbours' spikes show the
/// noise it is subject to.
class Accumulator {
  public:
    /// A bias is believed when the difference exceeds what a two-sided t-test at 95 % allows:
    /// the squared 0.975 quantile of Student's t with frames - 1 degrees of freedom (about
    /// 2 standard deviations once many frames are in, but 12.7 of them with 2 frames, where
    /// the variance itself rests on one difference and believing it would withdraw the blur
    /// from half the image on noise alone).
    static double blurTolerance(int frames);

    /// `noiseX` x `noiseY`: the window over which s^2 is pooled (1 x 1: the pixel alone).
    void reset(int width, int height, bool withdrawBlur = false, int noiseX = 1, int noiseY = 1);
    /// Adds rows [rowBegin, rowEnd) of a frame; call endFrame() once all rows are in.
    void addRows(const std::vector<glm::vec3>& frame, int rowBegin, int rowEnd);
    /// The same with the frame's unfiltered image too (withdrawBlur).
    void addRows(const std::vector<glm::vec3>& filtered, const std::vector<glm::vec3>& unfiltered,
                 int rowBegin, int rowEnd);
    void endFrame() { ++frames_; }
    /// The mean of the frames added so far, for rows [rowBegin, rowEnd).
    void meanRows(std::vector<glm::vec3>& out, int rowBegin, int rowEnd) const {
        meanRows(out, rowBegin, rowEnd, frames_);
    }
    /// The same after `frames` frames: frames() + 1 gives, before endFrame(), the mean the
    /// frame being added leads to, for rows whose window rows (meanWindow) are all added
    /// already. A compositor that writes the mean in the same sweep as it adds the rows reads
    /// them while they are still in the cache.
    void meanRows(std::vector<glm::vec3>& out, int rowBegin, int rowEnd, int frames) const;
    /// The rows [first, second) that row y's mean reads.
    std::pair<int, int> meanWindow(int y) const;
    int frames() const { return frames_; }
    bool withdrawsBlur() const { return withdrawBlur_; }

  private:
    /// The variance of pixel p's mean difference over its n frames, from them alone, given
    /// inv = 1 / n and invDegrees = 1 / (n - 1) (0 for n = 1).
    double ownVariance(std::size_t p, double inv, double invDegrees) const;

    int width_ = 0;
    int height_ = 0;
    int frames_ = 0;
    bool withdrawBlur_ = false;
    int noiseX_ = 1;
    int noiseY_ = 1;
    std::vector<double> sum_;             ///< 3 per pixel: the (filtered) frames
    std::vector<double> sumUnfiltered_;   ///< 3 per pixel, with withdrawBlur
    std::vector<double> sumDifference2_;  ///< 1 per pixel: sum of (lum filtered - lum unfiltered)^2
    std::vector<double> variance_;        ///< 1 per pixel: ownVariance after the last frame
};

}  // namespace igi
