#include "ErrorForecast.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace igi {

void ErrorForecast::add(int accumulated, double relMse) {
    if (accumulated < 2 || !std::isfinite(relMse)) return;
    points_.push_back({accumulated, relMse});
    // A still view of a live session accumulates for days: keep what the fit can still use
    // (the later half, as frames only grow within an accumulation), and beyond kMaxPoints every
    // other of them, which leaves the average over the later half an average of the same curve.
    const int latest = points_.back().frames;
    const auto used = std::find_if(points_.begin(), points_.end(),
                                   [&](const Point& p) { return 2 * p.frames >= latest; });
    points_.erase(points_.begin(), used);
    if (points_.size() > kMaxPoints) {
        std::vector<Point> thinned;
        thinned.reserve(points_.size() / 2 + 1);
        // From the newest back, so that the newest point always stays.
        for (std::size_t i = points_.size(); i-- > 0;)
            if ((points_.size() - 1 - i) % 2 == 0) thinned.push_back(points_[i]);
        points_.assign(thinned.rbegin(), thinned.rend());
    }
}

std::optional<double> ErrorForecast::coefficient() const {
    if (points_.empty()) return std::nullopt;
    const int latest = points_.back().frames;
    double sum = 0;
    int count = 0;
    for (auto it = points_.rbegin(); it != points_.rend() && 2 * it->frames >= latest; ++it) {
        sum += double(it->frames) * it->relMse;
        ++count;
    }
    return sum / double(count);
}

std::optional<double> ErrorForecast::framesTo(double target) const {
    const auto c = coefficient();
    if (!c || !(target > 0)) return std::nullopt;
    return std::max(double(points_.back().frames), *c / target);
}

std::optional<double> ErrorForecast::secondsTo(double target, double fps) const {
    const auto frames = framesTo(target);
    if (!frames || !(fps > 0)) return std::nullopt;
    if (points_.back().relMse <= target) return 0.0;
    return std::max(0.0, *frames - double(points_.back().frames)) / fps;
}

std::string ErrorForecast::describe(double target, double fps) const {
    if (points_.empty()) return {};
    std::string text = fmt::format("est. relMSE {:.3g}", points_.back().relMse);
    if (target > 0) {
        const auto seconds = secondsTo(target, fps);
        text += fmt::format(" (target {:.3g}, {})", target,
                            !seconds ? std::string("time to it unknown")
                            : *seconds >= 90
                                ? fmt::format("~{:.0f} min to it", std::ceil(*seconds / 60))
                                : fmt::format("~{:.0f} s to it", std::ceil(*seconds)));
    }
    return text;
}

}  // namespace igi
