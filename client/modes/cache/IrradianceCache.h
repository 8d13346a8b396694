#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <unordered_map>
#include <vector>

#include <glm/vec3.hpp>

#include "lighting/CacheSites.h"
#include "lighting/LightingMethod.h"
#include "lighting/LightingSet.h"
#include "lighting/LightingSetBuilder.h"
#include "tracing/MovedInstances.h"
#include "tracing/TraceableScene.h"

namespace igi {

/// Instant caching's records (paper 003, section 3): the irradiance that one collection of VPLs
/// gives each side of each cache site (CacheSites), computed the first time a pixel needs it,
/// and interpolated between sites for the pixels (interpolationWeights).
///
/// A record is a function of the scene state, the sites and the VPL collection only: the sum,
/// over the VPLs in the collection's order, of each unblocked VPL's light at the site through
/// the paper's bounded geometry term (BoundShape::Smooth). Any client that computes it gets the
/// same bits, whichever pixels asked for it and whatever it held before.
///
/// A cache made for a new scene state from the one before (`previous`) takes the records the
/// previous one had computed and brings them up to date as the paper's Algorithm 1 does,
/// instead of tracing them again:
/// - a record on an object that moved is dropped (case 5) and computed anew where needed;
/// - a VPL that is new or differs from the one of the same name before (its path met what
///   moved, a light or a material changed: cases 1 and 2) has its visibility ray traced again;
/// - for a VPL that did not change, the ray is traced against the moved objects only: blocked
///   where they are now, the VPL is hidden (case 3); if it was hidden before and the moved
///   objects blocked it where they were, it is traced against the whole scene (case 4); else
///   it keeps its visibility.
/// The result equals a record computed anew, bit for bit (tested).
class IrradianceCache final : public IndirectIrradiance, public LightingHistory {
  public:
    struct Config {
        float radius = 0;             ///< interpolation radius (world units)
        float maxAngleCos = 0.9f;     ///< normals farther apart than this are not interpolated
        float minDistance2 = 0;       ///< the bound's dmin, squared
        bool keepVisibility = false;  ///< keep each record's visibility bits for an update
    };

    /// A cache of records lit by `vpls` (their power already the collection's share) in the
    /// state `state` of `scene`. With `previous` (a cache of the same sites for an earlier
    /// state of the same scene, made with keepVisibility) its records are updated rather than
    /// traced again when this one first needs them.
    IrradianceCache(const TraceableScene& scene, std::shared_ptr<const SceneState> state,
                    std::shared_ptr<const CacheSites> sites,
                    std::vector<LightingSetBuilder::NamedVpl> vpls, const Config& config,
                    std::shared_ptr<const IrradianceCache> previous = nullptr);
    /// The records of `same` (a cache of a state that differs from `state` by the camera
    /// alone), shared, with `scene` to trace in: a camera that moves keeps every record.
    IrradianceCache(const TraceableScene& scene, std::shared_ptr<const SceneState> state,
                    const IrradianceCache& same);
    ~IrradianceCache() override;

    /// E interpolated from the records around `position` (computed as needed), or, where no
    /// record qualifies, the collection's light at the point itself.
    glm::vec3 irradiance(glm::vec3 position, glm::vec3 faceNormal,
                         RayCounters& counters) const override;

    /// The collection's light at a point itself, without the records (what irradiance() falls
    /// back to where no record qualifies).
    glm::vec3 irradianceAt(glm::vec3 position, glm::vec3 faceNormal, RayCounters& counters) const;

    /// Record r (2 site + side): computed, or updated from the previous cache, on first use.
    glm::vec3 record(std::uint32_t r, RayCounters& counters) const;
    /// Record r if this cache has it already, else null (no work).
    struct Data;
    std::shared_ptr<const Data> computedRecord(std::uint32_t r) const;
    /// Records computed anew and records brought up to date, so far.
    std::uint64_t recordsTraced() const { return counts_->traced.load(); }
    std::uint64_t recordsUpdated() const { return counts_->updated.load(); }

    const SiteGrid& grid() const { return grid_; }
    const std::vector<LightingSetBuilder::NamedVpl>& vpls() const { return vpls_; }
    const std::shared_ptr<const SceneState>& state() const { return state_; }
    const std::shared_ptr<const CacheSites>& sites() const { return sites_; }
    const Config& config() const { return config_; }

    struct Data {
        glm::vec3 irradiance{0.0f};
        std::vector<std::uint64_t> visible;  ///< bit k: VPL k reaches the site (keepVisibility)
    };

  private:
    struct Slot;
    /// The light of VPL k at (origin, n): what reaches the point if nothing blocks it, and
    /// the shadow ray's direction and length.
    struct Link {
        glm::vec3 light{0.0f};
        glm::vec3 direction{0.0f};
        float tfar = 0;
    };
    Link link(const Vpl& v, glm::vec3 origin, glm::vec3 n) const;
    std::shared_ptr<const Data> compute(std::uint32_t r, RayCounters& counters) const;
    std::shared_ptr<const Data> update(std::uint32_t r, const Data& before,
                                       RayCounters& counters) const;

    const TraceableScene& scene_;
    float diagonal_;  ///< scene_'s, kept: the previous cache's scene may be gone
    std::shared_ptr<const SceneState> state_;
    std::shared_ptr<const CacheSites> sites_;
    SiteGrid grid_;
    std::vector<LightingSetBuilder::NamedVpl> vpls_;
    Config config_;
    std::shared_ptr<Slot[]> slots_;
    /// What the update needs of the previous cache: its computed records and, per VPL of this
    /// collection, the index of the same VPL there if it did not change (-1 otherwise).
    struct Before {
        std::vector<std::shared_ptr<const Data>> records;
        std::vector<std::int32_t> sameAs;
        std::unique_ptr<MovedInstances> moved;
    };
    std::shared_ptr<const Before> before_;
    struct Counts {
        std::atomic<std::uint64_t> traced{0}, updated{0};
    };
    std::shared_ptr<Counts> counts_;
};

}  // namespace igi
