#include "lighting/LightingCache.h"

namespace igi {

std::shared_ptr<const LightingSet> LightingCache::get(std::uint32_t frame,
                                                      std::uint32_t accumulation,
                                                      std::uint32_t setIndex, bool& built) {
    std::promise<std::shared_ptr<const LightingSet>> promise;
    std::shared_future<std::shared_ptr<const LightingSet>> future;
    {
        std::lock_guard lock(mutex_);
        auto it = sets_.find({frame, setIndex});
        built = it == sets_.end();
        if (built) {
            future = promise.get_future().share();
            sets_.emplace(Key{frame, setIndex}, future);
        } else {
            future = it->second;
        }
    }
    if (built) {
        try {
            promise.set_value(
                std::make_shared<const LightingSet>(method_.build(frame, accumulation, setIndex)));
        } catch (...) {
            promise.set_exception(std::current_exception());
        }
    }
    return future.get();
}

void LightingCache::evictBefore(std::uint32_t frame) {
    std::lock_guard lock(mutex_);
    sets_.erase(sets_.begin(), sets_.lower_bound(Key{frame, 0}));
}

}  // namespace igi
