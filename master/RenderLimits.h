#pragma once

#include <chrono>
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "MasterOptions.h"
#include "ShownError.h"

namespace igi {

/// When a session's rendering ends: after --frames, when the image shown meets --target-error
/// (ShownError), or when --time-limit is up, whichever comes first; and what follows: the end of
/// the session, or, for a live one (--frames 0 with a control port or the web view), an idle
/// wait that a change can end (resume). Keeps the render clock, from the first frame opened to
/// the end of the rendering, which the time limit and the statistics read.
///
/// Reads the frame count and the target from the options it is given, which the master may
/// change after it is made (an animation's length, a settings command's target).
class RenderLimits {
  public:
    using Clock = std::chrono::steady_clock;

    explicit RenderLimits(const MasterOptions& options)
        : options_(options), shown_(options.targetError) {}

    /// The first frame is opened: the clock starts.
    void start();
    bool started() const { return started_; }
    /// The rendering has ended and a live session waits, idle.
    bool idle() const { return idle_; }

    /// Frame `frame` is still to be rendered: not past --frames, and not idle.
    bool frameLeft(std::uint32_t frame) const;
    /// `done` frames are done: all that --frames asked for.
    bool allFramesDone(std::uint32_t done) const {
        return options_.frames > 0 && done >= std::uint32_t(options_.frames);
    }
    /// The time limit is up while rendering (checked on the tick: it ends a frame midway).
    bool timeUp() const;
    /// Why rendering should end now (the target met, the time up, after `framesDone` frames),
    /// or empty.
    std::string reached(std::uint32_t framesDone) const;

    /// Ends the rendering for `why`. Returns true when the session is to end too; a live one
    /// stays, idle, and this returns false.
    bool end(const std::string& why);
    /// The session ends (stopped, or its frames done): the clock stops, unless idle stopped it.
    void sessionEnds();
    /// A change (`changed`) or a lower target: rendering resumes when the session is idle, its
    /// time is not up and the image shown no longer meets the target unless it changed.
    /// Returns whether it did.
    bool resume(bool changed);

    /// The image shown and its error estimate.
    ShownError& shown() { return shown_; }
    const ShownError& shown() const { return shown_; }

    /// Seconds of rendering: from the start to the end, or to now while rendering.
    double renderSeconds() const;
    Clock::time_point startTime() const { return start_; }
    Clock::time_point endTime() const { return end_; }

    /// The error estimate, the target, the time limit and the state, for the status reply.
    nlohmann::json json(double fps) const;

  private:
    bool live() const { return options_.frames == 0 && (options_.control || options_.view); }

    const MasterOptions& options_;
    ShownError shown_;  ///< of the image shown last
    bool started_ = false;
    bool idle_ = false;
    bool sessionEnding_ = false;
    Clock::time_point start_;
    Clock::time_point end_;
};

}  // namespace igi
