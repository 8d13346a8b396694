#include "FrameLogPace.h"

namespace igi {

FrameLogPace::FrameLogPace(double intervalSeconds) : interval_(intervalSeconds) {}

bool FrameLogPace::due(double seconds) {
    if (last_ >= 0 && seconds - last_ < interval_) {
        ++skipped_;
        return false;
    }
    last_ = seconds;
    skippedBefore_ = skipped_;
    skipped_ = 0;
    return true;
}

}  // namespace igi
