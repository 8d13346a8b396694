#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace igi {

/// The per-pixel planes a client computes and the master filters. Bit flags, so a tile result
/// can say which planes it carries (a plane that is zero everywhere is not sent).
enum Channel : std::uint32_t {
    kIrradiance = 1u << 0,   ///< E/pi at the eye path's diffuse end point (RGB, >= 0)
    kReflectance = 1u << 1,  ///< the end point's albedo times the path throughput (RGB, [0, 1])
    kNormal = 1u << 2,       ///< the end point's shading normal (unit vector, or zero if none)
    kDepth = 1u << 3,        ///< length of the eye path to the end point (> 0, +inf if none)
    kUnfiltered = 1u << 4,   ///< radiance that the master must not filter (RGB, >= 0)
    /// Radiance the end point's glossy lobe reflects toward the eye (RGB, >= 0): filtered like
    /// the irradiance (it carries the same interleaving pattern) but not multiplied by the
    /// reflectance, which is the Lambertian albedo only.
    kGlossy = 1u << 5,
};
constexpr std::uint32_t kAllChannels =
    kIrradiance | kReflectance | kNormal | kDepth | kUnfiltered | kGlossy;

/// Planar per-pixel results of one tile. A plane is either empty or has `count` entries.
/// The pixel seen by the master is
/// reflectance * filtered(irradiance) + filtered(glossy) + unfiltered.
struct TileChannels {
    int count = 0;
    std::vector<glm::vec3> irradiance;
    std::vector<glm::vec3> reflectance;
    std::vector<glm::vec3> normal;
    std::vector<float> depth;
    std::vector<glm::vec3> unfiltered;
    std::vector<glm::vec3> glossy;

    /// Allocates the planes named in `mask` for `n` pixels, zero-filled (depth +inf).
    void resize(int n, std::uint32_t mask);
    std::uint32_t mask() const;
};

}  // namespace igi
