#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

namespace igi {

/// A discrete distribution proportional to non-negative weights, sampled by inverting its
/// CDF, so stratified inputs give stratified choices.
class Distribution1D {
  public:
    Distribution1D() = default;
    explicit Distribution1D(const std::vector<float>& weights) {
        cdf_.resize(weights.size() + 1, 0.0);
        for (std::size_t i = 0; i < weights.size(); ++i)
            cdf_[i + 1] = cdf_[i] + double(std::max(0.0f, weights[i]));
        total_ = cdf_.back();
    }

    bool empty() const { return !(total_ > 0); }
    std::size_t size() const { return cdf_.empty() ? 0 : cdf_.size() - 1; }
    double total() const { return total_; }
    float pdf(std::size_t i) const { return float((cdf_[i + 1] - cdf_[i]) / total_); }

    /// The index for u in [0, 1); `remapped` receives u rescaled to [0, 1) within the chosen
    /// entry, so the same number can drive a further choice.
    std::size_t sample(float u, float* remapped = nullptr) const {
        const double target = double(u) * total_;
        auto it = std::upper_bound(cdf_.begin() + 1, cdf_.end(), target);
        std::size_t i = std::min<std::size_t>(std::size_t(it - cdf_.begin()) - 1, size() - 1);
        // Only rounding at u -> 1 can land past the end; step back to an entry of non-zero weight.
        while (i > 0 && cdf_[i + 1] == cdf_[i]) --i;
        if (remapped) {
            const double width = cdf_[i + 1] - cdf_[i];
            *remapped =
                width > 0 ? std::min(float((target - cdf_[i]) / width), 0x1.fffffep-1f) : 0.0f;
        }
        return i;
    }

  private:
    std::vector<double> cdf_;
    double total_ = 0;
};

}  // namespace igi
