#include "ShadowQueue.h"

#include <algorithm>

namespace igi {

void ShadowQueue::clear() {
    size_ = 0;
    top_ = 0;
    origins_.clear();
    pointBegin_.clear();
}

std::uint32_t ShadowQueue::beginPoint(glm::vec3 origin) {
    currentPoint_ = std::uint32_t(origins_.size());
    origins_.push_back(origin);
    pointBegin_.push_back(std::uint32_t(size_));
    return currentPoint_;
}

void ShadowQueue::sortByTarget() {
    const std::uint32_t top = top_;
    // Counting sort: bucket `top` holds the own targets, in the order queued.
    counts_.assign(std::size_t(top) + 2, 0);
    auto bucket = [top](std::uint32_t t) { return t == kOwnTarget ? top : t; };
    for (std::size_t i = 0; i < size_; ++i) ++counts_[bucket(entries_[i].target) + 1];
    for (std::size_t b = 1; b < counts_.size(); ++b) counts_[b] += counts_[b - 1];
    order_.resize(size_);
    for (std::uint32_t i = 0; i < size_; ++i) order_[counts_[bucket(entries_[i].target)]++] = i;
}

template <int N>
void ShadowQueue::traceAs(const TraceableScene& scene, bool sorted, RayCounters& counters) {
    thread_local TraceableScene::ShadowPacket<N> packet;  // its fixed fields are set once
    bool blocked[N];
    for (std::size_t i = 0; i < size_; i += N) {
        const int count = int(std::min(size_ - i, std::size_t(N)));
        for (int k = 0; k < count; ++k) {
            const Entry& e = entries_[sorted ? order_[i + std::size_t(k)] : i + std::size_t(k)];
            packet.set(k, origins_[e.point], e.direction, e.tfar);
        }
        if (count == 1) {  // a packet of one ray costs more than the ray alone
            const Entry& e = entries_[sorted ? order_[i] : i];
            blocked[0] = scene.occluded(origins_[e.point], e.direction, e.tfar, counters);
        } else {
            scene.occluded(packet, count, blocked, counters);
        }
        for (int k = 0; k < count; ++k)
            blocked_[sorted ? order_[i + std::size_t(k)] : i + std::size_t(k)] = blocked[k];
    }
}

void ShadowQueue::trace(const TraceableScene& scene, RayCounters& counters) {
    blocked_.assign(size_, 0);
    if (size_ == 0) return;
    // One point's rays share their origin already and go out in the order queued.
    const bool sorted = origins_.size() > 1;
    if (sorted) sortByTarget();
    if (scene.packetWidth() == 16)
        traceAs<16>(scene, sorted, counters);
    else
        traceAs<8>(scene, sorted, counters);
}

void ShadowQueue::sum(std::uint32_t point, glm::vec3& irradiance, glm::vec3& glossy) const {
    const std::size_t begin = pointBegin_[point];
    const std::size_t end = point + 1 < pointBegin_.size() ? pointBegin_[point + 1] : size_;
    glm::vec3 e(0.0f), g(0.0f);
    for (std::size_t i = begin; i < end; ++i) {
        if (blocked_[i]) continue;
        e += entries_[i].irradiance;
        g += entries_[i].glossy;
    }
    irradiance = e;
    glossy = g;
}

}  // namespace igi
