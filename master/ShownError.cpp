#include "ShownError.h"

#include <algorithm>
#include <optional>

#include <fmt/format.h>

namespace igi {

void ShownError::shown(int accumulated, const FrameCompositor& compositor,
                       const TileRegions& regions, double fps, FrameStats& stats) {
    if (accumulated <= 1) forecast_.reset();  // a new accumulation
    accumulated_ = accumulated;
    image_ = worstTile_ = 0;
    tilesAbove_ = 0;
    regionErrors_.clear();
    if (!estimated()) return;  // until both halves have a frame, there is no spread to see
    image_ = compositor.estimatedRelMse();
    stats.estimatedRelMse = image_;
    // Per tile region (the cells of one region share its pixels): the worst, and how many are
    // still above the target.
    for (int r = 0; r < regions.count(); ++r) {
        const double e = compositor.estimatedRelMse(regions.rectangle(r));
        worstTile_ = std::max(worstTile_, e);
        tilesAbove_ += target_ > 0 && e > target_;
        regionErrors_.push_back(e);
    }
    forecast_.add(accumulated, image_);
    if (target_ > 0) {
        if (const auto frames = forecast_.framesTo(target_)) stats.framesToTarget = *frames;
        if (const auto s = forecast_.secondsTo(target_, fps)) stats.secondsToTarget = *s;
    }
}

std::string ShownError::targetMet() const {
    // Asked as each frame is shown: the first frame whose estimate is at or below the target
    // ends the rendering, with its image.
    if (target_ > 0 && estimated() && image_ <= target_)
        return fmt::format("estimated relMSE {:.3g} <= --target-error {:.3g} after {} frames",
                           image_, target_, accumulated_);
    return {};
}

nlohmann::json ShownError::json(double fps) const {
    const auto orNull = [](const std::optional<double>& v) {
        return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
    };
    nlohmann::json j = {
        {"estimated_rel_mse", estimated() ? nlohmann::json(image_) : nlohmann::json()}};
    if (estimated()) {
        j["worst_tile_rel_mse"] = worstTile_;
        if (target_ > 0) j["tiles_above_target"] = {tilesAbove_, int(regionErrors_.size())};
    }
    if (target_ > 0) {
        j["predicted_frames_to_target"] = orNull(forecast_.framesTo(target_));
        j["predicted_seconds_to_target"] = orNull(forecast_.secondsTo(target_, fps));
    }
    return j;
}

}  // namespace igi
