#include "ErrorForecast.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace igi {

void ErrorForecast::add(int accumulated, double relMse) {
    if (accumulated < 2 || !std::isfinite(relMse)) return;
    points_.push_back({accumulated, relMse});
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
