#pragma once

#include <cstdint>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <utility>

#include "lighting/LightingMethod.h"
#include "lighting/LightingSet.h"

namespace igi {

/// The sets a client has built, by (frame, k). A set is built once, by the first tile that
/// needs it; tiles of the same k that arrive meanwhile wait for that build instead of repeating
/// it. The master's k-affine scheduling keeps the number of sets per frame small.
class LightingCache {
  public:
    explicit LightingCache(const LightingMethod& method) : method_(method) {}

    /// The set of (frame, setIndex); `built` tells whether this call built it. `accumulation`
    /// is the frame's place in its accumulation, the same for every tile of the frame.
    std::shared_ptr<const LightingSet> get(std::uint32_t frame, std::uint32_t accumulation,
                                           std::uint32_t setIndex, bool& built);

    /// Forgets the sets of frames before `frame`.
    void evictBefore(std::uint32_t frame);

  private:
    using Key = std::pair<std::uint32_t, std::uint32_t>;
    const LightingMethod& method_;
    std::mutex mutex_;
    std::map<Key, std::shared_future<std::shared_ptr<const LightingSet>>> sets_;
};

}  // namespace igi
