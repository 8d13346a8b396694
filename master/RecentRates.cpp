#include "RecentRates.h"

namespace igi {
namespace {

std::uint64_t valueOr0(const std::map<ClientId, std::uint64_t>& m, ClientId id) {
    const auto it = m.find(id);
    return it == m.end() ? 0 : it->second;
}

}  // namespace

RecentRates::RecentRates(double window, double spacing) : window_(window), spacing_(spacing) {}

void RecentRates::sample(double seconds, const Totals& totals) {
    if (!samples_.empty() && seconds - samples_.back().seconds < spacing_) return;
    samples_.push_back({seconds, totals});
    // Keep one sample at least a window old: the start of the next rates.
    while (samples_.size() > 1 && seconds - samples_[1].seconds >= window_) samples_.pop_front();
}

RecentRates::Rates RecentRates::rates(double seconds, const Totals& now) const {
    // The newest sample a window or more ago; early in a session, the oldest there is.
    const Sample* from = nullptr;
    for (const Sample& s : samples_) {
        if (from && seconds - s.seconds < window_) break;
        from = &s;
    }
    Rates r;
    if (!from || seconds - from->seconds <= 0) return r;
    const double dt = seconds - from->seconds;
    for (const auto& [id, rays] : now.rays) {
        r.raysPerSecond[id] = double(rays - valueOr0(from->totals.rays, id)) / dt;
        r.tilesPerSecond[id] =
            double(valueOr0(now.tiles, id) - valueOr0(from->totals.tiles, id)) / dt;
    }
    r.wireBytesPerSecond = double(now.bytes - from->totals.bytes) / dt;
    return r;
}

}  // namespace igi
