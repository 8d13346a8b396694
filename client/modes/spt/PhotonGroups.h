#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "lighting/LightingMethod.h"
#include "lighting/LightingSetBuilder.h"
#include "lights/Vpl.h"
#include "scene/SceneState.h"
#include "tracing/SurfacePoint.h"

namespace igi {

/// One group of selective photon tracing's pool (Dmitriev et al. 2002, section 5.1): the light
/// paths g + c G, c = 0 .. P - 1, of the Halton sequence (HaltonPaths), traced on one scene
/// state. Its first sptPilots paths are its pilots.
struct PhotonGroup {
    std::uint32_t index = 0;                  ///< g
    std::uint32_t tracedFrame = 0;            ///< the frame whose scene it was traced on: its age
    std::shared_ptr<const SceneState> scene;  ///< that scene
    /// The VPLs of its paths, each carrying its share of the pool (flux / (G P)).
    std::vector<Vpl> vpls;
    std::vector<std::uint32_t> vplPaths;  ///< c of the path each VPL is on
    /// Every mesh its paths hit (mirrors and glass included), sorted: the objects whose motion
    /// changes these paths where they were.
    std::vector<std::uint32_t> meshes;
};

/// Traces groups on one scene state: a function of (seed, settings, state) only, so every
/// client traces the same bits.
class GroupTracer {
  public:
    GroupTracer(const LightingSetBuilder& builder, std::shared_ptr<const SceneState> state,
                const RenderSettings& settings);

    /// Group g whole, as of `frame`.
    PhotonGroup trace(std::uint32_t g, std::uint32_t frame, RayCounters& rays) const;
    /// The meshes the pilots of group g hit, sorted.
    std::vector<std::uint32_t> pilotMeshes(std::uint32_t g, RayCounters& rays) const;

    const SceneState& state() const { return *state_; }
    const std::shared_ptr<const SceneState>& sharedState() const { return state_; }
    std::uint32_t groups() const { return groups_; }

  private:
    void tracePaths(std::uint32_t g, std::uint32_t count, RayCounters& rays,
                    PhotonGroup& out) const;

    const LightingSetBuilder& builder_;
    std::shared_ptr<const SceneState> state_;
    std::uint64_t seed_;
    std::uint32_t groups_, paths_, pilots_;
};

/// Whether a scene change invalidates a group traced on `group.scene`, now that the scene is
/// `now` (section 5.2, with the paper's phantoms replaced by what the group's own paths hit):
/// any light or material changed (every path may start or scatter differently), or a mesh that
/// moved since is one its paths hit then (they end elsewhere now) or one its pilots, traced on
/// `now`, hit (the group's paths may reach it now). `pilots` is called only when the answer
/// depends on it.
bool groupTouched(const PhotonGroup& group, const SceneState& now,
                  const std::function<std::vector<std::uint32_t>()>& pilots);

/// The pool of selective photon tracing at one frame: every group, and which of them a change
/// has invalidated and still wait to be traced again. Immutable: each frame's pool is made
/// from the one before, and tiles of older frames keep theirs.
///
/// Distribution independence: the pool of a frame is a function of the session's settings
/// and the scene state of every frame since the client's first (which groups a change
/// touches, which are traced again and in what order: oldest first, ties by index).
class PhotonGroups final : public LightingHistory,
                           public std::enable_shared_from_this<PhotonGroups> {
  public:
    /// What making this pool from the one before did.
    struct Update {
        std::uint32_t touched = 0;      ///< groups the change invalidated
        std::uint32_t traced = 0;       ///< groups traced (again)
        std::uint32_t pilotGroups = 0;  ///< groups whose pilots were traced to decide
        RayCounters rays;
    };

    /// The pool of a client's first frame: every group traced on its scene.
    static std::shared_ptr<const PhotonGroups> traceAll(const GroupTracer& tracer,
                                                        std::uint32_t frame);
    /// The pool at the first frame of a new scene state: the groups the change touches are
    /// marked, then a step.
    std::shared_ptr<const PhotonGroups> change(const GroupTracer& tracer, std::uint32_t frame,
                                               std::uint32_t budget) const;
    /// The pool one frame later: up to `budget` invalid groups traced again on the tracer's
    /// scene, the oldest first (ties by index). This pool itself when none is invalid.
    std::shared_ptr<const PhotonGroups> step(const GroupTracer& tracer, std::uint32_t frame,
                                             std::uint32_t budget) const;

    const std::vector<std::shared_ptr<const PhotonGroup>>& groups() const { return groups_; }
    bool invalid(std::uint32_t g) const { return invalid_.at(g); }
    std::uint32_t invalidCount() const;
    const Update& update() const { return update_; }
    /// Light paths in the pool.
    std::uint32_t paths(std::uint32_t pathsPerGroup) const {
        return std::uint32_t(groups_.size()) * pathsPerGroup;
    }

  private:
    /// Traces up to `budget` invalid groups again, the oldest first, into this (unshared) pool.
    void traceOldest(const GroupTracer& tracer, std::uint32_t frame, std::uint32_t budget);

    std::vector<std::shared_ptr<const PhotonGroup>> groups_;
    std::vector<bool> invalid_;
    std::shared_ptr<const SceneState> scene_;  ///< the scene of the pool's frame
    Update update_;
};

}  // namespace igi
