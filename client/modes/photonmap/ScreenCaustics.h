#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "igi/CausticPhoton.h"
#include "scene/Camera.h"
#include "tracing/TraceableScene.h"

namespace igi {

/// Larsen and Christensen's caustic filter (paper 002, section 5): the frame's caustic photons
/// are splatted where the camera sees them, and each spreads over the (2k + 1)^2 pixels around
/// its own with the weights sqrt(1 + 2 k^2 - (i^2 + j^2)) (their equation 4, k = 3: 7 x 7), in
/// screen space rather than in a world-space gather radius.
///
/// Their scale s is made exact here, so that the filter keeps a caustic's energy: a photon's
/// weights are normalized over its window, and a pixel turns the flux it receives into
/// irradiance by dividing by its own footprint on its surface (footprint()). The sum over the
/// pixels of irradiance times footprint is then the visible photons' flux (tested).
///
/// A photon counts if the camera sees the point it landed on from the side it arrived at (a
/// shadow ray from the camera, traced once per photon and frame by the first pixel that asks).
/// It runs on the clients, per tile: the photons are the frame's (every set's, the same on
/// every client), so a pixel's value does not depend on which client renders its tile; no
/// client needs another's pixels, and the master stays as it is (docs/MODES.md says why).
class ScreenCaustics {
  public:
    ScreenCaustics(const TraceableScene& scene, const Camera& camera, int width, int height,
                   std::vector<CausticPhoton> photons, int halfWidth = 3);

    /// The caustic irradiance E at pixel (x, y), whose surface's footprint is `footprint`.
    glm::vec3 irradiance(int x, int y, float footprint, RayCounters& counters) const;
    /// The area of the surface that pixel (x, y) sees at `distance`, with unit normal `normal`.
    float footprint(int x, int y, float distance, glm::vec3 normal) const;

    std::size_t photons() const { return photons_.size(); }

  private:
    struct Splat {
        glm::vec3 position, power, normal;
        int x, y;  ///< the pixel it projects into
    };
    bool visible(std::uint32_t i, RayCounters& counters) const;
    /// Unnormalized direction through pixel position (px, py), on the plane at distance 1.
    glm::vec3 ray(float px, float py) const;

    const TraceableScene& scene_;
    glm::vec3 origin_, forward_, right_, up_;  ///< right_ and up_ scaled by the half extents
    int width_, height_, half_;
    float pixelArea_;  ///< of one pixel on the plane at distance 1
    std::vector<Splat> photons_;
    std::vector<float> weights_;     ///< (2 half + 1)^2, normalized to sum to one
    static constexpr int kCell = 8;  ///< pixels per side of a bucket
    int cellsX_ = 0, cellsY_ = 0;
    std::vector<std::uint32_t> bucketStart_, sorted_;
    std::unique_ptr<std::atomic<std::uint8_t>[]> visibility_;  ///< 0 unknown, 1 seen, 2 hidden
};

}  // namespace igi
