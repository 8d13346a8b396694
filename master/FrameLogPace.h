#pragma once

namespace igi {

/// At most one frame line per interval, for a live session on a terminal: one line a frame
/// there scrolls hundreds of lines a second past the user (a --frames 0 session at a small size
/// wrote 405 KB in 49 s). A log file keeps every frame line: tests and scripts/perf_report.py
/// read them.
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
