#include "tracing/EmbreeDevice.h"

#include <stdexcept>
#include <string>

#include <spdlog/spdlog.h>

namespace igi {
namespace {

void onEmbreeError(void*, RTCError code, const char* message) {
    spdlog::error("Embree error {}: {}", int(code), message ? message : "");
}

}  // namespace

EmbreeDevice::EmbreeDevice() {
    device_ = rtcNewDevice(nullptr);
    if (!device_)
        throw std::runtime_error("cannot create the Embree device (error " +
                                 std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
    rtcSetDeviceErrorFunction(device_, onEmbreeError, nullptr);
}

EmbreeDevice::~EmbreeDevice() {
    rtcReleaseDevice(device_);
}

}  // namespace igi
