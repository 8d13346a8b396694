#include "RenderLimits.h"

#include <algorithm>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

namespace igi {

void RenderLimits::start() {
    started_ = true;
    start_ = Clock::now();
}

bool RenderLimits::frameLeft(std::uint32_t frame) const {
    return !idle_ &&
           (options_.frames == 0 || frame - options_.firstFrame < std::uint32_t(options_.frames));
}

bool RenderLimits::timeUp() const {
    return started_ && options_.timeLimitSeconds > 0 && !idle_ &&
           renderSeconds() >= options_.timeLimitSeconds;
}

std::string RenderLimits::reached(std::uint32_t framesDone) const {
    if (!started_ || idle_) return {};
    if (std::string why = shown_.targetMet(); !why.empty()) return why;
    if (options_.timeLimitSeconds > 0 && renderSeconds() >= options_.timeLimitSeconds)
        return fmt::format("--time-limit {:g} s reached after {} frames", options_.timeLimitSeconds,
                           framesDone);
    return {};
}

bool RenderLimits::end(const std::string& why) {
    if (live()) {
        end_ = Clock::now();
        idle_ = true;
        spdlog::info("{}: rendering ends; the session stays live, idle (igi-ctl stop ends it)",
                     why);
        return false;
    }
    spdlog::info("{}: ending the session", why);
    return true;
}

void RenderLimits::sessionEnds() {
    if (sessionEnding_) return;
    if (!idle_) end_ = Clock::now();
    sessionEnding_ = true;
}

bool RenderLimits::resume(bool changed) {
    if (!idle_ || sessionEnding_) return false;
    // Time up is up for good (idle time counts). A change restarts the accumulation, which the
    // target judges anew; without one, a target the image shown meets is met still.
    if (options_.timeLimitSeconds > 0 && renderSeconds() >= options_.timeLimitSeconds) return false;
    if (!changed && !shown_.targetMet().empty()) return false;
    idle_ = false;
    return true;
}

double RenderLimits::renderSeconds() const {
    if (!started_) return 0.0;
    const Clock::time_point end = idle_ || sessionEnding_ ? end_ : Clock::now();
    return std::max(0.0, std::chrono::duration<double>(end - start_).count());
}

nlohmann::json RenderLimits::json(double fps) const {
    // From the image shown last (ShownError::shown): the compositor may be adding the next
    // frame now, on the pool.
    nlohmann::json j = shown_.json(fps);
    j["target_error"] =
        options_.targetError > 0 ? nlohmann::json(options_.targetError) : nlohmann::json();
    j["adaptive_tiles"] = options_.adaptiveTiles;
    j["time_limit_s"] = options_.timeLimitSeconds > 0 ? nlohmann::json(options_.timeLimitSeconds)
                                                      : nlohmann::json();
    j["render_seconds"] = renderSeconds();
    j["rendering"] = idle_ ? "idle" : (started_ ? "running" : "waiting");
    return j;
}

}  // namespace igi
