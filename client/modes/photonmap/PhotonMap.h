#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "lights/Vpl.h"

namespace igi {

/// Photon hits in a hashed uniform grid for k-nearest-neighbour density estimates (Jensen's
/// photon map, as Larsen and Christensen reconstruct the full illumination: "the irradiance
/// using an N-nearest neighbour query of the photons, the total energy of these photons divided
/// by the area they span"). A hit is a Vpl whose `power` is its photon's flux times kd / pi, so
/// the estimate is radiance: L = sum of the k nearest hits' power / (pi r_k^2).
///
/// Only hits on the side `n` faces (their normal within 60 degrees of n) count, so a thin wall
/// lit on one side is dark on the other, and a floor does not count a wall's hits at a crease.
/// Candidates are visited in a fixed order and the k nearest chosen by (distance, index), so
/// every client that holds the same hits computes the same bits.
class PhotonMap {
  public:
    PhotonMap() = default;
    /// `area`: the surface area the hits are spread over (for the grid's cell size).
    PhotonMap(std::vector<Vpl> hits, double area, int k);

    /// Radiance of a Lambertian surface at p with unit normal n (on its lit side): the k
    /// nearest hits' power over pi r_k^2, searching up to 8 cells out; with fewer than k hits
    /// that far, all of them over that radius.
    glm::vec3 radiance(glm::vec3 p, glm::vec3 n) const;

    std::size_t size() const { return hits_.size(); }
    int k() const { return k_; }

  private:
    static std::uint32_t hashCell(std::int64_t x, std::int64_t y, std::int64_t z);
    std::uint32_t bucketOf(std::int64_t x, std::int64_t y, std::int64_t z) const {
        return hashCell(x, y, z) & mask_;
    }

    int k_ = 0;
    float cell_ = 0, invCell_ = 0;
    std::uint32_t mask_ = 0;
    std::vector<Vpl> hits_;                   ///< sorted by bucket
    std::vector<std::uint32_t> bucketStart_;  ///< mask_ + 2 entries
};

}  // namespace igi
