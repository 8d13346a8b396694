#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "lighting/LightingMethod.h"
#include "lighting/LightingSetBuilder.h"
#include "lights/Vpl.h"
#include "scene/SceneState.h"

namespace igi {

/// The surfaces one photon met, in order: what tells that a change diverted it.
struct PhotonPath {
    std::vector<std::uint32_t> meshes, triangles;
    std::vector<glm::vec3> positions;
    bool operator==(const PhotonPath&) const = default;
};

/// One group of Larsen and Christensen's selective photon emission (paper 002, section 2): the
/// photons g + c G, c = 0 .. P - 1, of the Halton sequence (HaltonPaths: photons of a group
/// leave in similar directions), traced on one scene state, with the paths they took and the
/// photon hits they left on non-delta surfaces (as VPLs: each hit's power is the photon's flux
/// times kd / pi, so that the radiance of a Lambertian surface is the sum of its hits' power
/// over pi r^2).
struct EmissionGroup {
    std::uint32_t index = 0;
    std::uint32_t tracedFrame = 0;
    std::vector<PhotonPath> paths;  ///< photon c's path
    std::vector<Vpl> hits;
};

/// Traces groups and single photons on one scene state: a function of (seed, settings, state)
/// only, so every client traces the same bits.
class EmissionTracer {
  public:
    EmissionTracer(const LightingSetBuilder& builder, std::shared_ptr<const SceneState> state,
                   const RenderSettings& settings);

    /// Group g whole, as of `frame`.
    EmissionGroup trace(std::uint32_t g, std::uint32_t frame, RayCounters& rays) const;
    /// The path photon c of group g takes now.
    PhotonPath path(std::uint32_t g, std::uint32_t c, RayCounters& rays) const;

    const std::shared_ptr<const SceneState>& state() const { return state_; }
    std::uint32_t groups() const { return groups_; }
    std::uint32_t photons() const { return photons_; }

  private:
    const LightingSetBuilder& builder_;
    std::shared_ptr<const SceneState> state_;
    std::uint64_t seed_;
    std::uint32_t groups_, photons_;
};

/// The photons of selective photon emission at one frame. Each frame, every group retraces one
/// of its photons, round robin (photon frame mod P), on that frame's scene; a group whose
/// photon took another path than it did is traced again whole, so that more photons go where
/// the scene changed (the paper's section 2). Immutable: each frame's state is made from the
/// one before, and tiles of older frames keep theirs.
///
/// Distribution independence: the state of a frame is a function of the session's settings and
/// the scene state of every frame since the session began, so every client that computes the
/// frames in order holds the same photons (a client that joins replays the history).
class PhotonEmission final : public LightingHistory,
                             public std::enable_shared_from_this<PhotonEmission> {
  public:
    struct Update {
        std::uint32_t checked = 0;  ///< photons retraced to check their group
        std::uint32_t traced = 0;   ///< groups traced again whole
        RayCounters rays;
    };

    /// Every group traced at `frame`.
    static std::shared_ptr<const PhotonEmission> traceAll(const EmissionTracer& tracer,
                                                          std::uint32_t frame);
    /// The state at `frame` (the next frame after this one's) on the tracer's scene: this very
    /// state when no group's photon diverged.
    std::shared_ptr<const PhotonEmission> step(const EmissionTracer& tracer,
                                               std::uint32_t frame) const;

    const std::vector<std::shared_ptr<const EmissionGroup>>& groups() const { return groups_; }
    /// Every group's hits, in group order.
    std::vector<Vpl> hits() const;
    const Update& update() const { return update_; }
    /// Changes with every group traced again: equal versions hold equal photons.
    std::uint64_t version() const { return version_; }
    const std::shared_ptr<const SceneState>& state() const { return state_; }
    /// Whether every photon has been checked on the light as it is since it last changed:
    /// until the next change, no photon can diverge and every later state is this one.
    bool settled(const SceneState& now, std::uint32_t frame, std::uint32_t photons) const {
        return state_->sameLighting(now) && frame >= lightingSince_ + photons;
    }

  private:
    std::vector<std::shared_ptr<const EmissionGroup>> groups_;
    std::shared_ptr<const SceneState> state_;  ///< the scene of this state's frame
    std::uint32_t lightingSince_ = 0;          ///< the frame the light last changed at
    Update update_;
    std::uint64_t version_ = 0;
};

}  // namespace igi
