#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "lights/Vpl.h"
#include "materials/SurfaceBrdf.h"

namespace igi {

/// Many VPLs by importance (issue 17): a set keeps a pool of VPLs, and each point connects to a
/// few of them chosen by what each could give it there, not to all.
///
/// A VPL's importance at a point x (shading normal n, geometric normal f) is
///   lum(power + glossyPower) cos_x cos_y / max(d^2, dmin^2),
/// the clamped Lambertian geometry term times its brightness; zero where the VPL cannot light
/// x at all (behind x's surface or x behind the VPL's), positive wherever it can, so the choice
/// only steers the estimate. GGX lobes at either end are ranked by what they send that way:
/// a GGX VPL by lum(Vpl::towards(w)) (its Lambertian power plus its lobe evaluated toward x,
/// not the flux it received, which is what glossyPower holds), a GGX receiver times its
/// sharpness toward the VPL (pi f normalized to unit albedo, SurfaceBrdf::sharpness), each
/// floored at 1e-6 of the Lambertian importance so that no VPL that can light x drops out.
/// Phong lobes keep the Lambertian proxy (their figures were measured with it). The chosen
/// distribution mixes kUniformShare of a uniform choice among the VPLs that can light x into the
/// importance, so that a VPL the estimate underrates (a glossy lobe, a blocked neighbour's light)
/// keeps a bounded weight.
///
/// `perPoint` VPLs are drawn by systematic sampling (numbers (j + offset) / perPoint,
/// j = 0 .. perPoint - 1, through the distribution's CDF): each VPL i is chosen
/// floor or ceil of perPoint p_i times, and one shadow ray carries it, weighted
/// count / (perPoint p_i). The sum over the chosen is an unbiased estimate of the sum over the
/// pool. The offset is the set's (LightingSetBuilder: stratified over the frame's sets), so a
/// choice is a function of the point, the set and the frame only.
struct VplChoice {
    std::uint32_t perPoint = 0;  ///< 0: every point connects to every VPL of the set
    float offset = 0.5f;         ///< in [0, 1)
    /// The set's VPLs side by side, padded with zero brightness to a multiple of four (the
    /// positions and normals to a multiple of eight): position, normal, brightness; also what
    /// the connections of a Lambertian point read (LambertianLinks).
    std::vector<float> px, py, pz, nx, ny, nz, lum;
    /// Per four VPLs: bit i where VPL 4k + i needs the general connection rather than the
    /// Lambertian one (LambertianLinks): a glossy VPL, a VPL on a normal- or bump-mapped
    /// surface (its normal bends toward each receiver, Vpl::bends), or an omni light sample (a
    /// point light, whose cosine is 1, when a set's light samples are laid out).
    std::vector<std::uint8_t> general;
    bool anyGeneral = false;
    /// Per four VPLs: bit i where VPL 4k + i has a GGX lobe; those VPLs themselves, in `ggxVpls`,
    /// at ggxSlot[4k + i], for ranking them by their lobe toward the point.
    std::vector<std::uint8_t> ggxBits;
    std::vector<std::uint32_t> ggxSlot;
    std::vector<Vpl> ggxVpls;
    std::uint32_t generalBits(std::size_t first) const { return general[first / 4]; }

    static constexpr float kUniformShare = 0.1f;

    bool active(std::size_t vpls) const { return perPoint > 0 && perPoint < vpls; }
    /// Whether prepare() laid out these `vpls` (sets made elsewhere have no lanes).
    bool laidOut(std::size_t vpls) const { return vpls > 0 && lum.size() == (vpls + 3) / 4 * 4; }
    /// Lays out `vpls` for the choice of `perPoint` per point with this set's `offset`.
    void prepare(const std::vector<Vpl>& vpls, std::uint32_t perPoint, float offset);
    /// Lays out `vpls` for the Lambertian connections only (no choice among them).
    void layOut(const std::vector<Vpl>& vpls) { prepare(vpls, 0, 0.5f); }

    /// A chosen VPL: its index in the set and the factor its contribution is scaled by.
    struct Pick {
        std::uint32_t index;
        float scale;
    };
    /// The VPLs chosen for the point at `origin` (shading normal n, geometric normal f, both
    /// on the side that receives), in increasing index order; `dmin2` is the set's bound
    /// distance squared; `receiver` the point's BRDF (only a GGX one changes the ranking).
    /// Returns their number (at most perPoint), written to `out`.
    std::uint32_t choose(glm::vec3 origin, glm::vec3 n, glm::vec3 f, float dmin2, Pick* out,
                         const SurfaceBrdf* receiver = nullptr) const;
};

}  // namespace igi
