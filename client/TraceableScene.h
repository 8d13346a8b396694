#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include "SceneGeometry.h"
#include "SurfacePoint.h"
#include "math/RayOffset.h"
#include "scene/Scene.h"
#include "scene/SceneState.h"

namespace igi {

/// The traceable form of one version of a scene: the meshes of a SceneGeometry placed by
/// instances (with the state's transforms) in a top-level Embree scene, the quad lights as
/// instances of a unit square, and the state's materials. Building one costs a top-level
/// commit, so each scene epoch gets its own. Read-only once built, safe from many threads.
class TraceableScene {
  public:
    TraceableScene(const SceneGeometry& geometry, const SceneState& state);
    /// A version in the scene's own, as-loaded state.
    explicit TraceableScene(const SceneGeometry& geometry);
    ~TraceableScene();
    TraceableScene(const TraceableScene&) = delete;
    TraceableScene& operator=(const TraceableScene&) = delete;

    /// Closest hit along origin + t * direction, t in (0, tfar). `direction` need not be unit;
    /// hit.distance is in units of its length.
    bool intersect(glm::vec3 origin, glm::vec3 direction, float tfar, SurfacePoint& hit,
                   RayCounters& counters) const;
    /// Whether anything lies along origin + t * direction, t in (0, tfar).
    bool occluded(glm::vec3 origin, glm::vec3 direction, float tfar, RayCounters& counters) const {
        return occludedIn(top_, origin, direction, tfar, counters);
    }
    /// The same in another Embree scene (one shadow ray, counted).
    static bool occludedIn(RTCScene scene, glm::vec3 origin, glm::vec3 direction, float tfar,
                           RayCounters& counters);
    /// Up to 8 shadow rays from one origin in one Embree packet (about 1.4x the rays per second
    /// of single rays, igi-bench): blocked[i] tells whether anything lies along
    /// origin + t * directions[i], t in (0, tfar[i]), for i < count.
    static constexpr int kPacket = 8;
    void occluded8(glm::vec3 origin, const glm::vec3* directions, const float* tfar, int count,
                   bool* blocked, RayCounters& counters) const;

    /// A triangle in world space, for lights and caustic targets.
    struct WorldTriangle {
        glm::vec3 p0, p1, p2;
        std::uint32_t material;
        std::uint32_t mesh;
        std::uint32_t triangle;
    };
    /// Every triangle of the scene (quad lights included).
    std::vector<WorldTriangle> triangles() const;
    /// Every triangle whose material emits (quad lights included, as two triangles each).
    std::vector<WorldTriangle> emissiveTriangles() const;
    /// Every triangle whose material is a mirror or glass.
    std::vector<WorldTriangle> specularTriangles() const;

    const std::vector<Material>& materials() const { return materials_; }
    const SceneGeometry& geometry() const { return geometry_; }
    /// The unit square onto a quad light: x along edge1, y along edge2, z along its normal.
    static glm::mat4 quadLightMatrix(const QuadLight& q);
    /// The top-level Embree scene, for benchmarks that trace it directly.
    RTCScene embreeScene() const { return top_; }
    /// Index of the first material made for the quad lights; quad light i uses this + i.
    std::uint32_t quadLightMaterialBase() const { return quadLightMaterialBase_; }

    /// A ray origin moved off the surface at p (geometric normal n, toward n): see
    /// offsetRayOrigin. The second form moves it to the side `direction` leaves to.
    glm::vec3 offsetOrigin(glm::vec3 p, glm::vec3 n) const {
        return offsetRayOrigin(p, n, diagonal_);
    }
    glm::vec3 offsetOrigin(glm::vec3 p, glm::vec3 n, glm::vec3 direction) const {
        return offsetRayOrigin(p, n, direction, diagonal_);
    }

    /// The scene's scale: the diagonal of its bounds. Clamping and photon radii are fractions
    /// of it, so they mean the same at every scale.
    float diagonal() const { return diagonal_; }
    /// Area-weighted mean Lambertian albedo of the diffuse surfaces (the fraction of light paths
    /// continued at each diffuse bounce in the quasi-random walk).
    float meanAlbedo() const { return meanAlbedo_; }
    std::uint64_t triangleCount() const { return triangleCount_; }

  private:
    struct MeshData {
        const Mesh* mesh = nullptr;
        glm::mat4 objectToWorld{1.0f};
        glm::mat3 normalToWorld{1.0f};
        int material = -1;  ///< every triangle's material, or -1: the mesh's own per triangle
    };

    void addInstance(const Mesh& mesh, RTCScene scene, const glm::mat4& objectToWorld,
                     int material);
    std::uint32_t materialOf(const MeshData& m, std::uint32_t triangle) const {
        return m.material >= 0 ? std::uint32_t(m.material) : m.mesh->materialIds[triangle];
    }
    WorldTriangle worldTriangle(std::uint32_t mesh, std::uint32_t triangle) const;
    void fillSurfacePoint(const RTCRayHit& rh, SurfacePoint& hit) const;
    std::vector<WorldTriangle> trianglesWhere(bool (*predicate)(const Material&)) const;
    void computeMeanAlbedo(const std::vector<Texture>& textures);

    const SceneGeometry& geometry_;
    std::vector<Material> materials_;
    const std::vector<Texture>* textures_ = nullptr;
    std::uint32_t quadLightMaterialBase_ = 0;
    std::vector<MeshData> meshes_;
    RTCScene top_ = nullptr;
    float diagonal_ = 1.0f;
    float meanAlbedo_ = 0.5f;
    std::uint64_t triangleCount_ = 0;
};

}  // namespace igi
