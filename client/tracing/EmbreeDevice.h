#pragma once

#include <embree3/rtcore.h>

namespace igi {

/// Owns the Embree device; one error callback for everything created on it (the pattern of the
/// Embree tutorials). Errors are logged; creation failure throws.
class EmbreeDevice {
  public:
    EmbreeDevice();
    ~EmbreeDevice();
    EmbreeDevice(const EmbreeDevice&) = delete;
    EmbreeDevice& operator=(const EmbreeDevice&) = delete;

    RTCDevice get() const { return device_; }

  private:
    RTCDevice device_ = nullptr;
};

}  // namespace igi
