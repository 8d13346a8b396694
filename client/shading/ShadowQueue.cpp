#include "shading/ShadowQueue.h"

#include <algorithm>
#include <cstddef>

#include "math/Lanes.h"

#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

namespace igi {

void ShadowQueue::clear() {
    size_ = 0;
    origins_.clear();
    pointBegin_.clear();
}

std::uint32_t ShadowQueue::beginPoint(glm::vec3 origin) {
    currentPoint_ = std::uint32_t(origins_.size());
    origins_.push_back({origin.x, origin.y, origin.z, 0.0f});
    pointBegin_.push_back(std::uint32_t(size_));
    return currentPoint_;
}

void ShadowQueue::sortByTarget() {
    // One past the largest shared target (kOwnTarget + 1 wraps to 0: not a shared target).
    std::uint32_t top = 0;
    for (std::size_t i = 0; i < size_; ++i) top = std::max(top, targets_[i] + 1u);
    // Counting sort: bucket `top` holds the own targets, in the order queued.
    counts_.assign(std::size_t(top) + 2, 0);
    auto bucket = [top](std::uint32_t t) { return t == kOwnTarget ? top : t; };
    for (std::size_t i = 0; i < size_; ++i) ++counts_[bucket(targets_[i]) + 1];
    for (std::size_t b = 1; b < counts_.size(); ++b) counts_[b] += counts_[b - 1];
    order_.resize(size_);
    for (std::uint32_t i = 0; i < size_; ++i) order_[counts_[bucket(targets_[i])]++] = i;
}

namespace {

// Four rows of four floats, turned into four columns written at a .. d (d may be null: the
// column dropped): lanes lane .. lane + 3 of a packet's SoA fields.
void storeColumns(const float* const row[4], float* a, float* b, float* c, float* d) {
#if defined(__SSE2__)
    __m128 r0 = _mm_loadu_ps(row[0]), r1 = _mm_loadu_ps(row[1]), r2 = _mm_loadu_ps(row[2]),
           r3 = _mm_loadu_ps(row[3]);
    _MM_TRANSPOSE4_PS(r0, r1, r2, r3);
    _mm_store_ps(a, r0);
    _mm_store_ps(b, r1);
    _mm_store_ps(c, r2);
    if (d) _mm_store_ps(d, r3);
#else
    for (int m = 0; m < 4; ++m) {
        a[m] = row[m][0];
        b[m] = row[m][1];
        c[m] = row[m][2];
        if (d) d[m] = row[m][3];
    }
#endif
}

// Lanes lane .. lane + 3 of a packet's rays from four entries (each its direction and tfar,
// and its point's origin: four floats apiece), transposed four at a time rather than written
// field by field.
template <class Rays>
void setFour(Rays& rays, int lane, const float* const ray[4], const float* const origin[4]) {
    storeColumns(ray, &rays.dir_x[lane], &rays.dir_y[lane], &rays.dir_z[lane], &rays.tfar[lane]);
    storeColumns(origin, &rays.org_x[lane], &rays.org_y[lane], &rays.org_z[lane], nullptr);
}

}  // namespace

template <int N>
void ShadowQueue::traceAs(const TraceableScene& scene, bool sorted, RayCounters& counters) {
    thread_local TraceableScene::ShadowPacket<N> packet;  // its fixed fields are set once
    static_assert(offsetof(Entry, tfar) == offsetof(Entry, direction) + 12);
    bool blocked[N];
    std::uint32_t index[N];
    for (std::size_t i = 0; i < size_; i += N) {
        const int count = int(std::min(size_ - i, std::size_t(N)));
        for (int k = 0; k < count; ++k)
            index[k] = sorted ? order_[i + std::size_t(k)] : std::uint32_t(i + std::size_t(k));
        if (count == 1) {  // a packet of one ray costs more than the ray alone
            const Entry& e = entries_[index[0]];
            const Origin& o = origins_[e.point];
            blocked_[index[0]] = scene.occluded({o.x, o.y, o.z}, e.direction, e.tfar, counters);
            continue;
        }
        // Lanes past `count` repeat the last ray: they are switched off, but filled whole.
        for (int k = count; k < (count + 3) / 4 * 4; ++k) index[k] = index[count - 1];
        for (int k = 0; k < count; k += 4) {
            const float *ray[4], *origin[4];
            for (int m = 0; m < 4; ++m) {
                const Entry& e = entries_[index[k + m]];
                ray[m] = &e.direction.x;
                origin[m] = &origins_[e.point].x;
            }
            setFour(packet.rays, k, ray, origin);
        }
        scene.occluded(packet, count, blocked, counters);
        for (int k = 0; k < count; ++k) blocked_[index[k]] = blocked[k];
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
    sumRange(begin, end, irradiance, glossy);
}

void ShadowQueue::sum(std::uint32_t point, std::uint32_t leading, glm::vec3& leadIrradiance,
                      glm::vec3& leadGlossy, glm::vec3& irradiance, glm::vec3& glossy) const {
    const std::size_t begin = pointBegin_[point];
    const std::size_t end = point + 1 < pointBegin_.size() ? pointBegin_[point + 1] : size_;
    const std::size_t split = std::min(end, begin + leading);
    sumRange(begin, split, leadIrradiance, leadGlossy);
    sumRange(split, end, irradiance, glossy);
}

void ShadowQueue::sumRange(std::size_t begin, std::size_t end, glm::vec3& irradiance,
                           glm::vec3& glossy) const {
    // Without a branch per entry (whether a ray was blocked is unpredictable): a blocked
    // entry adds +0, which leaves every lane's sum as it was (a sum that starts at +0 and adds
    // only unblocked values is never -0). Lane by lane the additions are the scalar ones.
    using lanes::F4;
    using lanes::I4;
    static_assert(offsetof(Entry, glossy) == offsetof(Entry, irradiance) + 12);
    const I4 xyz = {-1, -1, -1, 0};
    F4 e = {0, 0, 0, 0}, g = {0, 0, 0, 0};
    for (std::size_t i = begin; i < end; ++i) {
        const I4 open = I4{0, 0, 0, 0} + (std::int32_t(blocked_[i]) - 1);  // blocked_ is 0 or 1
        // irradiance.xyz and glossy.x; then glossy.xyz and the point's index (dropped).
        const F4 a = lanes::load<F4>(&entries_[i].irradiance.x);
        const F4 b = lanes::load<F4>(&entries_[i].glossy.x);
        e += F4(I4(a) & open);
        g += F4(I4(b) & open & xyz);
    }
    irradiance = glm::vec3(e[0], e[1], e[2]);
    glossy = glm::vec3(g[0], g[1], g[2]);
}

}  // namespace igi
