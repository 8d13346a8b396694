#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/mat4x4.hpp>

#include "scene/Scene.h"
#include "scene/SceneState.h"
#include "tracing/AlphaCoverage.h"
#include "tracing/EmbreeDevice.h"
#include "tracing/EnvironmentMap.h"

namespace igi {

/// How one version of a scene is handed to Embree.
/// - Flat: every mesh and quad light in world space in one Embree scene, one BVH. A ray crosses
///   no instance: 1.4 to 1.9 times the shadow rays per second of the instanced layout on the
///   Cornell scenes (docs/PERFORMANCE.md, section 1), the same hits up to rounding. Only
///   geometry placed several times (Mesh::instanced) is an instance there too, of its one BVH.
/// - Instanced: each mesh's own BVH (in object space) placed by an instance in a top-level
///   scene. A move costs a top-level commit only, whatever the meshes' size.
/// A version is flat when its objects stand where the scene file put them (that BVH is built
/// once per session) or when the scene is small enough to rebuild one BVH per move
/// (kFlatRebuildTriangles); a large scene whose objects moved is instanced.
enum class SceneLayout { Flat, Instanced };

/// The part of a scene that never changes while it renders: one committed Embree scene per mesh
/// (in object space), a unit square that quad lights are instances of, and the flat scenes of
/// the placements in use (the as-loaded one and the latest other). Built once per session and
/// shared by every scene version.
class SceneGeometry {
  public:
    SceneGeometry(const EmbreeDevice& device, const Scene& scene);
    ~SceneGeometry();
    SceneGeometry(const SceneGeometry&) = delete;
    SceneGeometry& operator=(const SceneGeometry&) = delete;

    /// Scenes up to this many triangles (about 15 ms of BVH build on one core) get a flat BVH
    /// of their own after a move; larger ones are instanced until their objects return.
    static constexpr std::uint64_t kFlatRebuildTriangles = 32768;

    const EmbreeDevice& device() const { return device_; }
    const Scene& scene() const { return scene_; }
    /// The sky, with its sampling distribution (built once: a map's can take a while).
    /// The environment as loaded.
    const EnvironmentMap& environment() const { return environment_; }
    /// The environment a state describes (a live change of its radiance or rotation): the one
    /// as loaded when unchanged, else made from it (EnvironmentMap::changedTo) and kept for
    /// the epochs that follow with the same environment. Safe from many threads.
    EnvironmentMap environmentFor(const Environment& environment) const;
    /// The Embree scene of mesh i, or null for a mesh without triangles. The instances of one
    /// geometry (Mesh::instanced) share one: flat scenes place it by an Embree instance, whose
    /// hits report the mesh as instID[0] and the geometry below as in the instanced layout. A
    /// mesh with cut-out
    /// triangles (materials with hasCutOuts) holds its opaque ones under geometry ID
    /// kOpaqueGeometry and the cut-out ones, with the filter functions, under kCutOutGeometry;
    /// any other mesh is one geometry of ID 0 as before.
    RTCScene mesh(std::size_t i) const { return meshes_[i]; }
    static constexpr std::uint32_t kOpaqueGeometry = 0;
    static constexpr std::uint32_t kCutOutGeometry = 1;

    /// Whether any mesh has cut-out triangles (else every geometry ID is a mesh's, or a quad
    /// light's, and every primitive ID its triangle).
    bool anyCutOuts() const { return anyCutOuts_; }
    /// The meshes with cut-out triangles that are not instances, ascending. In a flat scene of
    /// `quadLights` quad lights, the cut-out triangles of cutOutMeshes()[r] are geometry ID
    /// meshes + quadLights + r.
    const std::vector<std::uint32_t>& cutOutMeshes() const { return cutOutMeshes_; }
    bool hasCutOuts(std::size_t mesh) const {
        return mesh < parts_.size() && parts_[mesh].cutOut != nullptr;
    }
    /// Mesh `mesh`'s triangle that is primitive `prim` of its opaque or its cut-out geometry.
    std::uint32_t meshTriangle(std::size_t mesh, bool cutOut, std::uint32_t prim) const {
        const Parts& p = parts_[mesh];
        if (!p.cutOut) return prim;
        return cutOut ? p.cutOut->triangles[prim] : p.opaque[prim];
    }
    /// The unit square (0,0,0), (1,0,0), (1,1,0), (0,1,0) as two counter-clockwise triangles.
    const Mesh& unitQuad() const { return unitQuad_; }
    RTCScene unitQuadScene() const { return unitQuadScene_; }
    /// Triangles of all meshes (quad lights not counted), every instance counted.
    std::uint64_t triangleCount() const { return triangleCount_; }
    /// Triangles in the meshes' own Embree scenes: an instanced geometry counted once.
    std::uint64_t builtTriangleCount() const { return builtTriangles_; }
    /// The Embree scenes shared by instances (one per instanced geometry).
    std::size_t instancedSceneCount() const { return instancedScenes_; }
    /// Whether some mesh is an instance (Mesh::instanced).
    bool anyInstanced() const { return anyInstanced_; }

    /// The layout of a version in `state`: a function of the scene and the state only, so every
    /// client chooses the same.
    SceneLayout layoutOf(const SceneState& state) const;
    /// The flat Embree scene of `state` (meshes then quad lights, geometry ID i for mesh i and
    /// meshes + j for quad light j), retained for the caller, who releases it. Thread-safe.
    RTCScene flatScene(const SceneState& state) const;

    /// Adds `mesh` placed by objectToWorld to `scene` under geometry ID `id`: in world space
    /// (flat) or as an instance of `object`, its object-space scene. An instanced mesh (Mesh::
    /// instanced) is always an instance of its geometry's scene. MovedInstances adds moved
    /// objects in the same way as the version it stands for, so both find the same hits.
    void attachWorldMesh(RTCScene scene, const Mesh& mesh, const glm::mat4& objectToWorld,
                         std::uint32_t id) const;
    /// The same for the scene's mesh i: its opaque triangles under `id`, its cut-out ones (if
    /// any) under `cutOutId`.
    void attachWorldMesh(RTCScene scene, std::size_t mesh, const glm::mat4& objectToWorld,
                         std::uint32_t id, std::uint32_t cutOutId) const;
    void attachInstance(RTCScene scene, RTCScene object, const glm::mat4& objectToWorld,
                        std::uint32_t id) const;

  private:
    /// Where every object stands: what a flat scene depends on.
    struct Placement {
        std::vector<glm::mat4> meshes, quadLights;
        bool operator==(const Placement&) const = default;
    };
    struct FlatScene;
    /// A mesh split by coverage; both empty when no triangle is cut out.
    struct Parts {
        std::vector<std::uint32_t> opaque;  ///< opaque primitive -> the mesh's triangle
        std::unique_ptr<CutOutTriangles> cutOut;
    };

    RTCScene build(const Mesh& mesh, const Parts* parts) const;
    void splitByCoverage();
    Placement placementOf(const SceneState& state) const;
    RTCScene buildFlat(const Placement& placement, RTCBuildQuality quality) const;

    const EmbreeDevice& device_;
    const Scene& scene_;
    EnvironmentMap environment_;
    mutable std::mutex environmentMutex_;
    mutable EnvironmentMap changedEnvironment_;  ///< the latest environmentFor() made
    std::vector<RTCScene> meshes_;
    std::vector<Parts> parts_;  ///< per mesh
    std::vector<std::uint32_t> cutOutMeshes_;
    Mesh unitQuad_;
    RTCScene unitQuadScene_ = nullptr;
    std::uint64_t triangleCount_ = 0;
    std::uint64_t builtTriangles_ = 0;
    std::size_t instancedScenes_ = 0;
    bool anyInstanced_ = false;
    bool anyCutOuts_ = false;
    Placement loaded_;  ///< as the scene file put them

    mutable std::mutex flatMutex_;
    mutable std::shared_ptr<FlatScene> loadedFlat_, latestFlat_;
};

}  // namespace igi
