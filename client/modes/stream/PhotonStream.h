#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "lighting/LightingMethod.h"
#include "lighting/LightingSetBuilder.h"
#include "lights/SurfaceLights.h"

namespace igi {

/// The photons one scene epoch adds to the stream, already deposited on the VSLs: per VSL and
/// side, the summed power (the flux x kd / pi that each photon impact nearest to it carries,
/// as an indirect VPL there would) of `paths` light paths traced on that epoch's scene.
struct PhotonBatch {
    std::vector<glm::vec3> front, back;
    std::uint32_t paths = 0;
};

/// Traces batch `index` of the stream (light paths from a sampler keyed by the session seed and
/// the index, ended by Russian roulette as in photon tracing) on the builder's scene, and
/// deposits each non-delta impact on its nearest VSL in `lights` (the VSLs placed in that
/// scene's state). A function of (seed, settings, scene, index) only.
PhotonBatch shootPhotonBatch(const LightingSetBuilder& builder,
                             const std::vector<SurfaceLight>& lights, std::uint64_t seed,
                             std::uint32_t index, std::uint32_t paths, RayCounters& rays);

/// The pool of photon streaming (Meneveaux and Bridault 2008) at one scene epoch: the batches
/// of the last W epochs (W = RenderSettings::streamWindow), the oldest dropped as a new one
/// comes, which is their first-in first-out pool of photon impacts with the update in O(1) per
/// impact done a batch at a time. The VSL sites stay the same all session; a moved object's
/// VSLs move with it and keep the power deposited on them, until the batches that brought it
/// leave the pool.
///
/// Distribution independence: an epoch's batch is shot on its scene and keyed by the frame the
/// epoch begins at alone, so every client that saw the same epochs holds the same pool. The
/// frame, not the epoch's number: a live session whose settings change at frame F (where every
/// client starts its pool afresh) then holds the pool a session started at F with those
/// settings holds, whatever epochs came before. The first epoch a client has fills the whole
/// pool with batches shot on that epoch's scene.
class PhotonStream final : public LightingHistory {
  public:
    /// The pool of a client's first epoch, `epoch`, which begins at frame `firstFrame`.
    static std::shared_ptr<const PhotonStream> first(
        std::shared_ptr<const std::vector<SurfaceLightSite>> sites, std::uint32_t epoch,
        std::uint32_t firstFrame, int window,
        const std::function<PhotonBatch(std::uint32_t index)>& shoot);
    /// The pool of the epoch after this one's, with `batch` (shot on that epoch's scene) in.
    std::shared_ptr<const PhotonStream> next(std::uint32_t epoch, int window,
                                             std::shared_ptr<const PhotonBatch> batch) const;

    /// The index of the batch of the epoch that begins at frame `firstFrame` (never 0: the
    /// window - 1 batches before it in a first epoch's fill never collide with a later
    /// epoch's, which begins at a later frame).
    static std::uint32_t batchIndex(std::uint32_t firstFrame) {
        return firstFrame + std::uint32_t(kMaxStreamWindow);
    }

    const std::vector<SurfaceLightSite>& sites() const { return *sites_; }
    std::shared_ptr<const std::vector<SurfaceLightSite>> sharedSites() const { return sites_; }
    std::uint32_t epoch() const { return epoch_; }
    /// Light paths in the pool.
    std::uint32_t paths() const;
    /// Per VSL and side: the pool's power, per light path.
    void power(std::vector<glm::vec3>& front, std::vector<glm::vec3>& back) const;
    std::size_t batches() const { return batches_.size(); }

  private:
    std::shared_ptr<const std::vector<SurfaceLightSite>> sites_;
    std::uint32_t epoch_ = 0;
    std::vector<std::shared_ptr<const PhotonBatch>> batches_;  ///< oldest first
};

}  // namespace igi
