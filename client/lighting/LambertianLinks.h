#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "lights/VplChoice.h"
#include "math/Lanes.h"

namespace igi {

/// The connections a point with a Lambertian BRDF makes to a set's VPLs, computed for many VPLs
/// at once from their lanes (VplChoice: positions and normals laid out side by side).
///
/// Why its own kernel: a Lambertian point tests every VPL of its set, and most tests fail on a
/// cosine, after a square root and three divisions; four (SSE2) or eight (AVX2) VPLs share
/// their latencies. Lane by lane it is the arithmetic of EndPointShader's scalar connection
/// (glm's dot is (x x' + y y') + z z'; -a is 0 - a; the clamp is max(d^2, dmin^2)), so every
/// value has the bits the scalar connection gives, whichever instruction set ran it.
struct LambertianLink {
    std::uint32_t vpl;  ///< index in the set
    float d;            ///< distance to the VPL
    glm::vec3 w;        ///< unit direction toward it
    float g;            ///< cos_x cos_y / max(d^2, dmin^2)
};

/// Where lambertianLinks writes its links: side by side, each field in an array of its own, so
/// that the AVX2 kernel writes eight lanes with one store per field, the kept lanes packed to
/// the front, without a branch per kept lane (which lanes are kept is unpredictable). On the
/// Cornell boxes that measured within the noise of the branching version (igi-bench): the
/// kernel is bound by its square root and divisions, whose bits must be the scalar ones.
class LinkBuffer {
  public:
    /// Room for the links to `count` VPLs (plus a lane group: a packed store writes whole groups).
    void reserve(std::size_t count);
    std::size_t size() const { return size_; }
    LambertianLink operator[](std::size_t k) const {
        return {vpl_[k], d_[k], {wx_[k], wy_[k], wz_[k]}, g_[k]};
    }

  private:
    friend struct LinkWriter;
    std::size_t size_ = 0;
    std::vector<std::uint32_t> vpl_;
    std::vector<float> d_, wx_, wy_, wz_, g_;
};

/// The links from `origin` (shading normal n, geometric normal f) to VPLs 0 .. count - 1 of
/// `vpls` that the scalar tests keep: d^2 > 0 and both cosines and f.w above zero. A glossy
/// VPL or an omni light sample (a bit of vpls.generalBits) is listed whatever its tests give,
/// for the caller to take the general connection. Writes them to `out` in VPL order (its size
/// says how many, as does the value returned). `isa` chooses the instruction set
/// (lanes::bestIsa() unless a test says otherwise).
std::size_t lambertianLinks(const VplChoice& vpls, std::size_t count, glm::vec3 origin, glm::vec3 n,
                            glm::vec3 f, float dmin2, LinkBuffer& out,
                            lanes::Isa isa = lanes::bestIsa());

}  // namespace igi
