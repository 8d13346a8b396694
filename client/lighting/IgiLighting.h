#pragma once

#include "lighting/LightingMethod.h"
#include "lighting/LightingSetBuilder.h"

namespace igi {

/// Instant global illumination (paper 004): every frame's sets come from fresh light paths,
/// nothing is kept from one frame to the next.
class IgiLighting final : public LightingMethod {
  public:
    explicit IgiLighting(const LightingSetBuilder& builder) : builder_(builder) {}

    LightingSet build(std::uint32_t frame, std::uint32_t accumulation,
                      std::uint32_t setIndex) const override {
        return builder_.build(frame, accumulation, setIndex);
    }

  private:
    const LightingSetBuilder& builder_;
};

}  // namespace igi
