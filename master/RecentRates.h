#pragma once

#include <cstdint>
#include <deque>
#include <map>

#include "TileScheduler.h"

namespace igi {

/// Rates over a fixed recent window (the last half second, as igi-ctl status and the web
/// view's overlay say), from running totals sampled as the session goes. Rates computed since
/// the previous question instead read 0 on the first one and a long average on a late one.
class RecentRates {
  public:
    /// What has been counted so far.
    struct Totals {
        std::map<ClientId, std::uint64_t> rays, tiles;
        std::uint64_t bytes = 0;  ///< tile results received, all clients
    };
    struct Rates {
        std::map<ClientId, double> raysPerSecond;
        std::map<ClientId, double> tilesPerSecond;
        double wireBytesPerSecond = 0;
    };

    /// Samples at most every `spacing` seconds, rates over `window` seconds.
    explicit RecentRates(double window = 0.5, double spacing = 0.05);

    /// The totals at `seconds` (a clock that only goes forward). Cheap when called often:
    /// samples closer than the spacing to the previous one are not kept.
    void sample(double seconds, const Totals& totals);
    /// Rates from the newest sample at least `window` before `seconds` (or the oldest, early in
    /// a session) to `now`, the totals at `seconds`. Clients absent from `now` (gone) have none.
    Rates rates(double seconds, const Totals& now) const;

  private:
    struct Sample {
        double seconds;
        Totals totals;
    };
    double window_, spacing_;
    std::deque<Sample> samples_;
};

}  // namespace igi
