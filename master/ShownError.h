#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ErrorForecast.h"
#include "FrameCompositor.h"
#include "Statistics.h"
#include "render/TileRegions.h"

namespace igi {

/// The error estimate of the image shown last and the forecast of its accumulation: what the
/// progress line, the statistics, `igi-ctl status` and --target-error read. Kept when the image
/// is shown, since the compositor's own figures change while it adds the next frame on the
/// pool.
class ShownError {
  public:
    /// `targetError`: --target-error (0: none).
    explicit ShownError(double targetError) : target_(targetError) {}
    /// A new target (a settings command's; 0: none), for the images shown from now on.
    void setTarget(double targetError) { target_ = targetError; }

    /// The image of `accumulated` frames was shown: takes the compositor's estimate for the
    /// image and per tile region of `regions`, and writes it and the forecast into `stats`.
    void shown(int accumulated, const FrameCompositor& compositor, const TileRegions& regions,
               double fps, FrameStats& stats);
    /// The estimate of each region (TileRegions' order) of the image shown last; empty before
    /// two frames. What adaptive tiles decide on.
    const std::vector<double>& regionErrors() const { return regionErrors_; }

    /// Why the target is met ("estimated relMSE ... <= --target-error ..."), or empty.
    std::string targetMet() const;
    /// For the progress line (ErrorForecast::describe).
    std::string describe(double fps) const { return forecast_.describe(target_, fps); }
    /// estimated_rel_mse, worst_tile_rel_mse, tiles_above_target and the predictions, for the
    /// status reply.
    nlohmann::json json(double fps) const;

  private:
    /// Whether the frame shown has an estimate: both of its halves have a frame.
    bool estimated() const { return accumulated_ >= RowAccumulator::kFirstEstimateFrames; }
    double target_;
    ErrorForecast forecast_;  ///< of the current accumulation
    int accumulated_ = 0;
    double image_ = 0;
    double worstTile_ = 0;  ///< the largest over the tile regions
    int tilesAbove_ = 0;    ///< regions above the target
    std::vector<double> regionErrors_;
};

}  // namespace igi
