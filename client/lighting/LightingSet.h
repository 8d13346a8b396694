#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "igi/CausticGrid.h"
#include "lights/Vpl.h"
#include "lights/VplChoice.h"
#include "shading/ConnectionBound.h"
#include "tracing/SurfacePoint.h"

namespace igi {

/// Where a method keeps the indirect light of Lambertian surfaces when it does not connect each
/// pixel to its set's VPLs (instant caching's records, the photon map's final gathers): the
/// irradiance E (not divided by pi) at a point. Thread-safe.
class IndirectIrradiance {
  public:
    virtual ~IndirectIrradiance() = default;
    /// E at `position`, on the side that the unit geometric normal `faceNormal` points to.
    virtual glm::vec3 irradiance(glm::vec3 position, glm::vec3 faceNormal,
                                 RayCounters& counters) const = 0;
    /// Whether the method also knows the radiance every surface sends out (a photon map does):
    /// then a glossy lobe's continuation ray takes it where it lands (surfaceRadiance), as the
    /// glossy lobe has no VPLs to connect to.
    virtual bool knowsSurfaceRadiance() const { return false; }
    virtual glm::vec3 surfaceRadiance(glm::vec3 position, glm::vec3 faceNormal,
                                      RayCounters& counters) const {
        (void)position, (void)faceNormal, (void)counters;
        return glm::vec3(0.0f);
    }
};

class ScreenCaustics;

/// Everything the pixels of one interleaving identification k use in one frame: the set P_k
/// (points on the lights for direct light, VPLs for indirect light) and the set C_k of caustic
/// photons. A client builds it itself from the session seed, the frame (and the frame's place
/// in the accumulation, which the master sends) and k, so every client that renders a tile of
/// k builds exactly the same set, and no one waits for anyone.
struct LightingSet {
    std::vector<Vpl> direct;  ///< samples on the lights (connections not bounded)
    /// `direct` laid out side by side, for the connections of Lambertian points
    /// (LambertianLinks); not laid out (sets made elsewhere), they connect one at a time.
    VplChoice directLanes;
    /// With a light tree (Lights::choosesPerPoint) instead of `direct`: the numbers each point
    /// turns into its own light samples (choice, then a point on the chosen light).
    std::vector<glm::vec3> directNumbers;
    /// One sample of each exact light (Lights::exactLight), which every point connects to
    /// besides `direct`: its light is the same in every set (a soft sun's disk point aside), so
    /// it is kept out of the filtered irradiance (EndPointLight::sharp).
    std::vector<Vpl> exact;
    std::vector<Vpl> indirect;  ///< VPLs from light paths (connections bounded)
    /// With VPLs by importance: how each point chooses among `indirect` (VplChoice); inactive,
    /// every point connects to every one.
    VplChoice vplChoice;
    CausticGrid caustics;  ///< photons from the lights that reached a non-delta surface through
                           ///< mirrors and glass (caustics)
    /// Photons from the VPLs that did (diffuse-specular-diffuse light): smooth light, a few
    /// photons per set, gathered in a wider radius of their own.
    CausticGrid indirectCaustics;
    /// The connection bound's distance, squared, and its sharpness budget (ConnectionBound), for
    /// this frame.
    float minDistance2 = 0;
    float sharpnessBudget = std::numeric_limits<float>::infinity();
    BoundShape boundShape = BoundShape::Clamp;
    /// When set, Lambertian end points take the light of the indirect VPLs from here instead
    /// of connecting to `indirect` (which still lights glossy end points and the compensation).
    std::shared_ptr<const IndirectIrradiance> indirectIrradiance;
    /// When set, the caustics of the pixels that see a surface directly come from this screen-
    /// space filter (Larsen and Christensen) instead of `caustics`, which is then empty.
    std::shared_ptr<const ScreenCaustics> screenCaustics;
    /// Whether the settings ask for indirect light at all (VPL paths longer than the light):
    /// the bound's compensation only completes the VPLs' estimate.
    bool indirectLight = false;
    /// Whether the light paths went on past the walk by Russian roulette.
    bool roulette = false;
    /// The share of points without a glossy lobe that trace a compensation ray (0: none; the
    /// points with one always do when there is a compensation at all).
    float compensationShare = 0;
    /// Whether the points shade where their compensation rays land, where the settings ask for
    /// Kollig-Keller's compensation: not in IGI's first frame after a change, which leaves the
    /// bound's cut unrestored (LightingSetBuilder::assemble).
    bool compensationRays = true;
    std::uint32_t lightPaths = 0;  ///< light paths traced for `indirect`
    std::uint32_t photonsShot = 0;
    RayCounters buildRays;  ///< rays traced to build the set
};

}  // namespace igi
