#pragma once

#include <cstdint>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/vec3.hpp>

#include "scene/SceneState.h"
#include "tracing/SceneGeometry.h"
#include "tracing/SurfacePoint.h"

namespace igi {

/// The objects (meshes and quad lights) whose placement differs between two states of a scene,
/// as two small Embree scenes: where they were and where they are. Instant caching's update
/// (paper 003, Algorithm 1) traces a cached visibility ray against these alone to learn whether
/// a move can have changed it. The objects are laid out exactly as in the TraceableScene of each
/// state (SceneLayout), so a ray blocked in the whole scene by a moved object is blocked here,
/// and the other way round.
class MovedInstances {
  public:
    MovedInstances(const SceneGeometry& geometry, const SceneState& before,
                   const SceneState& after);
    ~MovedInstances();
    MovedInstances(const MovedInstances&) = delete;
    MovedInstances& operator=(const MovedInstances&) = delete;

    bool any() const { return !meshes_.empty() || lightsMoved_ > 0; }
    /// Whether mesh i was moved.
    bool meshMoved(std::uint32_t mesh) const;

    /// Whether a moved object blocks origin + t direction, t in (0, tfar), where it was
    /// (`before`) or where it is.
    bool occluded(bool before, glm::vec3 origin, glm::vec3 direction, float tfar,
                  RayCounters& counters) const;

  private:
    RTCScene build(const SceneGeometry& geometry, const SceneState& state) const;

    std::vector<std::uint32_t> meshes_;  ///< sorted
    std::vector<std::uint32_t> lights_;  ///< quad lights whose geometry moved
    std::size_t lightsMoved_ = 0;
    RTCScene before_ = nullptr, after_ = nullptr;
};

}  // namespace igi
