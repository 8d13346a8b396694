#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace igi {

/// When will the accumulated image reach a target error? The estimated relMSE of an
/// accumulation (FrameCompositor::estimatedRelMse) falls like c / frames while its noise
/// dominates; this fits c to the curve so far and says how many frames, and so how many
/// seconds, the target is away. The fit takes the later half of the frames (k e_k averaged
/// over k >= n / 2): the first frames carry the first frame's clamp bias and the progressive
/// filter's withdrawal, and the latest say most about the rate that holds now. A bias that no
/// frame removes flattens the curve; the fit then predicts too early, and says so by moving
/// on as frames come in.
class ErrorForecast {
  public:
    /// A new accumulation (the scene or the view changed).
    void reset() { points_.clear(); }
    /// The estimate after `accumulated` frames (>= 2; others are ignored: no spread yet).
    void add(int accumulated, double relMse);

    /// c of relMSE ~ c / frames, once two frames are in.
    std::optional<double> coefficient() const;
    /// Accumulated frames at which the fit reaches `target` (at least the frames in now).
    std::optional<double> framesTo(double target) const;
    /// Seconds until then at `fps` frames a second (0 once there; none without a rate).
    std::optional<double> secondsTo(double target, double fps) const;

    /// For the progress and log lines: "est. relMSE 0.0031" and, with a target (> 0),
    /// " (target 0.001, ~12 s)"; empty before an estimate.
    std::string describe(double target, double fps) const;

    /// The points kept: at most kMaxPoints, however long the accumulation.
    std::size_t pointsKept() const { return points_.size(); }
    static constexpr std::size_t kMaxPoints = 1024;

  private:
    struct Point {
        int frames;
        double relMse;
    };
    std::vector<Point> points_;
};

}  // namespace igi
