#pragma once

namespace igi {

/// At most one frame line per interval, for a live session (--frames 0): one line a frame
/// scrolls hundreds of lines a second past a user on a terminal, and fills a log file without
/// end (a session at a small size wrote 405 KB in 49 s). The frames left out are logged at debug
/// level, for tests that follow every frame; a finite run keeps every frame line at info
/// (scripts/perf_report.py reads them).
class FrameLogPace {
  public:
    explicit FrameLogPace(double intervalSeconds = 1.0);

    /// Whether the frame shown at `seconds` (a clock that only goes forward) gets its line.
    bool due(double seconds);
    /// The frames shown without a line before the last one due.
    int skippedBefore() const { return skippedBefore_; }

  private:
    double interval_;
    double last_ = -1;
    int skipped_ = 0;
    int skippedBefore_ = 0;
};

}  // namespace igi
