#pragma once

#include <vector>

#include <glm/vec3.hpp>

namespace igi {

/// Averages successive frames while nothing changes, so a still view converges (the
/// accumulation buffer of the paper). Sums are kept in double so that thousands of frames
/// lose no precision.
class Accumulator {
  public:
    void reset(int width, int height);
    /// Adds rows [rowBegin, rowEnd) of a frame; call endFrame() once all rows are in.
    void addRows(const std::vector<glm::vec3>& frame, int rowBegin, int rowEnd);
    void endFrame() { ++frames_; }
    /// The mean of the frames added so far, for rows [rowBegin, rowEnd).
    void meanRows(std::vector<glm::vec3>& out, int rowBegin, int rowEnd) const;
    int frames() const { return frames_; }

  private:
    int width_ = 0;
    int height_ = 0;
    int frames_ = 0;
    std::vector<double> sum_;  ///< 3 per pixel
};

}  // namespace igi
