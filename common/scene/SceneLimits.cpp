#include "scene/SceneLimits.h"

#include <utility>

namespace igi {

Budget::Budget(std::uint64_t limit, std::string unit, std::string scope)
    : limit_(limit), unit_(std::move(unit)), scope_(std::move(scope)) {}

bool Budget::fits(std::uint64_t amount) const {
    // Written so that a hostile amount near 2^64 cannot wrap around.
    return amount <= limit_ - used_;
}

void Budget::add(std::uint64_t amount) {
    used_ += amount;
}

std::string Budget::exceeded(std::uint64_t amount) const {
    return std::to_string(amount) + " more " + unit_ + " would exceed the limit of " +
           std::to_string(limit_) + " " + scope_ + " (" + std::to_string(used_) + " already)";
}

}  // namespace igi
