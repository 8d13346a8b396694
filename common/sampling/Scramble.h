#pragma once

#include <cstdint>

#include "sampling/Hash.h"

namespace igi {

/// Independent sample streams: each has its own random bit vectors, so light paths, caustic
/// photons, light samples and eye paths are decorrelated.
enum class SampleStream : std::uint32_t {
    VplPaths = 1,
    CausticPhotons = 2,
    DirectLight = 3,
    EyePath = 4,
    PathTracer = 5,
    IndirectCausticPhotons = 6,  ///< photons shot from VPLs at mirrors and glass
    PhotonStream = 7,            ///< photon streaming's batches (keyed by batch, not frame)
    SelectivePhotons = 8,        ///< selective photon tracing's Halton paths (keyed by index)
    StableVplPaths = 9,          ///< instant caching's light paths, the same in every frame
    VplChoice = 10,              ///< the offset of each set's choice of VPLs (VplChoice)
    LightEdgeRays = 11,          ///< the eye rays that gather the light seen at its edges
    ExactLights = 12,            ///< each set's point on each exact light (a soft sun's disk)
};

/// The random bit vector for one dimension of one stream in one frame. Every client derives the
/// same vectors from the session seed and the frame number: no communication is needed, and a
/// new frame gets new vectors (so accumulation converges).
inline std::uint32_t scrambleBits(std::uint64_t seed, std::uint32_t frame, SampleStream stream,
                                  std::uint32_t dimension) {
    return static_cast<std::uint32_t>(
        hashValues(seed, frame, static_cast<std::uint32_t>(stream), dimension) >> 32);
}

}  // namespace igi
