#pragma once

#include <vector>

#include <embree3/rtcore.h>

#include "EmbreeDevice.h"
#include "scene/Scene.h"

namespace igi {

/// The part of a scene that never changes while it renders: one committed Embree scene per mesh
/// (in object space) and a unit square that quad lights are instances of. Built once per
/// session; every scene version instances these, so moving an object or a light costs an
/// instance transform and a top-level commit, not a rebuild.
class SceneGeometry {
  public:
    SceneGeometry(const EmbreeDevice& device, const Scene& scene);
    ~SceneGeometry();
    SceneGeometry(const SceneGeometry&) = delete;
    SceneGeometry& operator=(const SceneGeometry&) = delete;

    const EmbreeDevice& device() const { return device_; }
    const Scene& scene() const { return scene_; }
    /// The Embree scene of mesh i, or null for a mesh without triangles.
    RTCScene mesh(std::size_t i) const { return meshes_[i]; }
    /// The unit square (0,0,0), (1,0,0), (1,1,0), (0,1,0) as two counter-clockwise triangles.
    const Mesh& unitQuad() const { return unitQuad_; }
    RTCScene unitQuadScene() const { return unitQuadScene_; }

  private:
    RTCScene build(const Mesh& mesh) const;

    const EmbreeDevice& device_;
    const Scene& scene_;
    std::vector<RTCScene> meshes_;
    Mesh unitQuad_;
    RTCScene unitQuadScene_ = nullptr;
};

}  // namespace igi
