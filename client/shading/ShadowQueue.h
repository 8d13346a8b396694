#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "tracing/TraceableScene.h"

namespace igi {

/// The shadow rays of many shading points, queued with what each brings if nothing blocks it,
/// traced together, then summed point by point.
///
/// Why: the points of one tile share their set's lights and VPLs, so the rays that end at one
/// target from neighbouring points are nearly parallel. Traced in packets by target (each packet
/// from up to 16 points to one light or VPL) they run about 1.3-1.6 times as fast as packets of
/// one point's rays to all targets, whose directions spread over the hemisphere (igi-bench on
/// the Cornell scenes; docs/PERFORMANCE.md, section 1).
///
/// The sums do not depend on the packets: a point's contributions are added in the order they
/// were queued, each unblocked one exactly once, as single rays would give them.
class ShadowQueue {
  public:
    /// A target no other point shares (a light sample a point chose for itself).
    static constexpr std::uint32_t kOwnTarget = 0xFFFFFFFFu;

    /// Empties the queue, keeping its memory.
    void clear();
    /// Starts the connections of the next point, all from `origin`; returns the point's index.
    std::uint32_t beginPoint(glm::vec3 origin);
    /// A connection of the current point: the ray along `direction` for t in (0, tfar) toward
    /// `target` (the index of a light or VPL in the points' common set, or kOwnTarget), and the
    /// irradiance and glossy radiance it adds when unblocked.
    void add(std::uint32_t target, glm::vec3 direction, float tfar, glm::vec3 irradiance,
             glm::vec3 glossy) {
        if (size_ == entries_.size()) grow(std::max<std::size_t>(64, 2 * size_));
        targets_[size_] = target;
        // Field by field rather than `= {...}`: for the aggregate GCC may build a temporary on
        // the stack and copy it with loads wider than the stores that wrote it, a
        // store-forwarding stall (as EndPointShader's linkTo had). addEach's loop keeps the
        // aggregate: there it takes fewer instructions (callgrind, Cornell scene).
        Entry& e = entries_[size_++];
        e.direction = direction;
        e.tfar = tfar;
        e.irradiance = irradiance;
        e.glossy = glossy;
        e.point = currentPoint_;
    }
    /// A connection as add() takes it.
    struct Connection {
        std::uint32_t target;
        glm::vec3 direction;
        float tfar;
        glm::vec3 irradiance, glossy;
    };
    /// `n` connections of the current point in a row, the k-th given by at(k): add()'s
    /// effect, with the room made once and the queue's fields kept in registers (add() must
    /// reload them after each entry it writes).
    template <class At>
    void addEach(std::size_t n, At&& at) {
        if (size_ + n > entries_.size()) grow(std::max(2 * size_, size_ + n + 64));
        Entry* out = entries_.data() + size_;
        std::uint32_t* targets = targets_.data() + size_;
        const std::uint32_t point = currentPoint_;
        for (std::size_t k = 0; k < n; ++k) {
            const Connection c = at(k);
            out[k] = {c.direction, c.tfar, c.irradiance, c.glossy, point};
            targets[k] = c.target;
        }
        size_ += n;
    }
    /// Traces every queued ray, in packets of the scene's width grouped by target.
    void trace(const TraceableScene& scene, RayCounters& counters);
    /// The point's unblocked contributions, each added in the order queued, starting from zero.
    void sum(std::uint32_t point, glm::vec3& irradiance, glm::vec3& glossy) const;
    /// The same in two parts: the point's first `leading` entries into leadIrradiance and
    /// leadGlossy, the rest into irradiance and glossy.
    void sum(std::uint32_t point, std::uint32_t leading, glm::vec3& leadIrradiance,
             glm::vec3& leadGlossy, glm::vec3& irradiance, glm::vec3& glossy) const;

    std::size_t size() const { return size_; }
    std::size_t points() const { return pointBegin_.size(); }

  private:
    struct Entry {
        glm::vec3 direction;
        float tfar;
        glm::vec3 irradiance, glossy;
        std::uint32_t point;
    };
    void grow(std::size_t capacity) {
        entries_.resize(capacity);
        targets_.resize(capacity);
    }
    /// Indices of the entries sorted by target (stable; own targets last): order_.
    void sortByTarget();
    /// Entries [begin, end)'s unblocked contributions, added in order from zero.
    void sumRange(std::size_t begin, std::size_t end, glm::vec3& irradiance,
                  glm::vec3& glossy) const;
    template <int N>
    void traceAs(const TraceableScene& scene, bool sorted, RayCounters& counters);

    // Entries are kept in a vector that only grows: add() writes in place, without a
    // push_back's bookkeeping, and clear() keeps the memory.
    std::vector<Entry> entries_;
    /// Each entry's target, apart: the sort reads them alone, three times.
    std::vector<std::uint32_t> targets_;
    std::size_t size_ = 0;
    std::uint32_t currentPoint_ = 0;
    /// A point's origin, padded to four floats: traceAs reads each with one load.
    struct Origin {
        float x, y, z, pad;
    };
    std::vector<Origin> origins_;            ///< per point
    std::vector<std::uint32_t> pointBegin_;  ///< point p's entries start there
    std::vector<std::uint8_t> blocked_;
    std::vector<std::uint32_t> order_, counts_;
};

}  // namespace igi
