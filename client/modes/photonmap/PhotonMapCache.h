#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>

#include <glm/vec3.hpp>

#include "lighting/CacheSites.h"
#include "lighting/LightingSet.h"
#include "modes/photonmap/PhotonMap.h"
#include "tracing/TraceableScene.h"

namespace igi {

/// Larsen and Christensen's reconstruction of the light (paper 002, sections 3 and 4), kept at
/// the cache sites instead of texture maps:
/// - the approximated illumination (AIM) of each site's side: the radiance the photon map gives
///   there (k nearest photon hits);
/// - the indirect illumination (IIM): a final gather from the site, `gatherRays` rays over the
///   hemisphere (cosine-distributed, stratified; mirrors and glass followed to the next
///   non-delta surface), each taking the AIM where it lands (interpolated between that
///   surface's sites): the irradiance that the rest of the scene sends the site, lights seen
///   directly excluded (the pixels' light samples carry those).
/// Pixels interpolate the IIM between sites as instant caching interpolates its records. Both
/// are computed the first time they are needed, as a function of the photons, the scene and
/// the sites only: the same bits on every client.
class PhotonMapCache final : public IndirectIrradiance {
  public:
    struct Config {
        float radius = 0;          ///< interpolation radius (world units)
        float maxAngleCos = 0.9f;  ///< normals farther apart than this are not interpolated
        int gatherRays = 64;
        int maxEyeDepth = 8;  ///< mirror and glass bounces a gather ray follows
        std::uint64_t seed = 1;
    };

    PhotonMapCache(const TraceableScene& scene, std::shared_ptr<const SceneState> state,
                   std::shared_ptr<const CacheSites> sites, std::shared_ptr<const PhotonMap> map,
                   const Config& config);
    /// The records of `same` (same photons, a state that differs by the camera alone), shared,
    /// with `scene` to trace in.
    PhotonMapCache(const TraceableScene& scene, std::shared_ptr<const SceneState> state,
                   const PhotonMapCache& same);
    ~PhotonMapCache() override;

    /// The indirect irradiance E at a point: the IIM interpolated between sites (where no site
    /// qualifies, gathered at the point itself).
    glm::vec3 irradiance(glm::vec3 position, glm::vec3 faceNormal,
                         RayCounters& counters) const override;
    /// The radiance a Lambertian surface at the point sends out, as the AIM says (interpolated
    /// between sites; where none qualifies, the photon map's own estimate there).
    bool knowsSurfaceRadiance() const override { return true; }
    glm::vec3 surfaceRadiance(glm::vec3 position, glm::vec3 faceNormal,
                              RayCounters& counters) const override;

    /// Record r (2 site + side) of each map.
    glm::vec3 approximated(std::uint32_t r) const;
    glm::vec3 indirect(std::uint32_t r, RayCounters& counters) const;
    /// Final gathers done so far (records of the IIM and points without a site).
    std::uint64_t gathers() const { return counts_->gathers.load(); }

    const std::shared_ptr<const SceneState>& state() const { return state_; }
    const std::shared_ptr<const PhotonMap>& map() const { return map_; }
    const std::shared_ptr<const CacheSites>& sites() const { return sites_; }
    const Config& config() const { return config_; }

  private:
    struct Slots;
    glm::vec3 gather(glm::vec3 position, glm::vec3 n, std::uint64_t key,
                     RayCounters& counters) const;

    const TraceableScene& scene_;
    std::shared_ptr<const SceneState> state_;
    std::shared_ptr<const CacheSites> sites_;
    SiteGrid grid_;
    std::shared_ptr<const PhotonMap> map_;
    Config config_;
    std::shared_ptr<Slots> slots_;
    struct Counts {
        std::atomic<std::uint64_t> gathers{0};
    };
    std::shared_ptr<Counts> counts_;
};

}  // namespace igi
