#pragma once

#include <cstdio>
#include <memory>
#include <string>

namespace igi {

class ProgressSink;

/// The terminal's progress line for a finite run: frames done of total, fps, time left,
/// clients, redrawn in place at the bottom while log lines print above it. Only on a
/// terminal: where stderr is a file or a pipe (CI, tests, logs), there is no line and every
/// frame keeps its plain log line.
///
/// No Debian package offers a C++ progress bar (indicators, progresscpp are not packaged), and
/// one line needs no library: a spdlog sink that clears the line before each log record and
/// draws it again after.
class ProgressLine {
  public:
    /// A progress line on stderr when stderr is a terminal and `totalFrames` > 0; else none.
    /// Replaces the default logger's sinks: call before setting the log pattern.
    /// `limited`: a target error or a time limit ends the run, so a line is drawn also
    /// without a frame total.
    static std::shared_ptr<ProgressLine> attachIfTerminal(int totalFrames, bool limited = false);

    /// A line drawn on `out`; attachIfTerminal makes one on stderr and routes the log through it.
    ProgressLine(int totalFrames, std::FILE* out);
    /// `error`: the estimated error and the time to the target (ErrorForecast::describe),
    /// appended when not empty.
    void update(int framesDone, double fps, int clients, const std::string& error = {});
    /// The run's length, once known (an --animation without --frames runs to its end).
    void setTotalFrames(int totalFrames) { totalFrames_ = totalFrames; }
    /// Prints `line` (a local client's own stderr line, whole, without its newline) above the
    /// progress line, as a log record is: a client writing to the terminal itself would cut
    /// into the line.
    void printAbove(const std::string& line);
    /// Leaves the last state on its own line.
    void finish();

    /// The line's text, e.g. "frame 12/100 [====>     ] 2.8 fps, 31 s left, 2 clients".
    static std::string format(int framesDone, int totalFrames, double fps, int clients);

  private:
    int totalFrames_;
    std::shared_ptr<ProgressSink> sink_;
};

}  // namespace igi
