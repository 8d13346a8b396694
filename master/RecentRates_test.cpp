#include "RecentRates.h"

#include <gtest/gtest.h>

namespace igi {
namespace {

RecentRates::Totals totals(std::uint64_t rays, std::uint64_t tiles, std::uint64_t bytes) {
    RecentRates::Totals t;
    t.rays[1] = rays;
    t.tiles[1] = tiles;
    t.bytes = bytes;
    return t;
}

// Issue 40: the first `igi-ctl status` showed 0 for every rate; later ones averaged since the
// previous call. A client doing 1000 rays and 10 tiles a second, sampled every 20 ms.
TEST(RecentRates, TheFirstQuestionAlreadyHasRatesAndTheyCoverTheLastHalfSecond) {
    RecentRates rates;
    double t = 0;
    for (; t < 3.0; t += 0.02)
        rates.sample(t, totals(std::uint64_t(1000 * t), std::uint64_t(10 * t), 0));
    const auto r = rates.rates(t, totals(std::uint64_t(1000 * t), std::uint64_t(10 * t), 0));
    EXPECT_NEAR(r.raysPerSecond.at(1), 1000, 50);
    EXPECT_NEAR(r.tilesPerSecond.at(1), 10, 2.5);

    // The client stops: a second later the rates say so, whenever the last question was.
    const double stop = t;
    for (; t < stop + 1.0; t += 0.02) rates.sample(t, totals(std::uint64_t(1000 * stop), 30, 5));
    const auto idle = rates.rates(t, totals(std::uint64_t(1000 * stop), 30, 5));
    EXPECT_EQ(idle.raysPerSecond.at(1), 0);
    EXPECT_EQ(idle.wireBytesPerSecond, 0);
}

TEST(RecentRates, EarlyInASessionTheRatesSpanWhatThereIs) {
    RecentRates rates;
    EXPECT_TRUE(rates.rates(0, totals(0, 0, 0)).raysPerSecond.empty()) << "no samples yet";
    rates.sample(0, totals(0, 0, 0));
    const auto r = rates.rates(0.2, totals(200, 2, 1000));
    EXPECT_DOUBLE_EQ(r.raysPerSecond.at(1), 1000);
    EXPECT_DOUBLE_EQ(r.wireBytesPerSecond, 5000);
}

}  // namespace
}  // namespace igi
