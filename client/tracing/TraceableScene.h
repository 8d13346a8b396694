#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include "math/RayOffset.h"
#include "scene/Scene.h"
#include "scene/SceneState.h"
#include "tracing/SceneGeometry.h"
#include "tracing/SunDisk.h"
#include "tracing/SurfacePoint.h"

namespace igi {

/// The traceable form of one version of a scene: the meshes of a SceneGeometry placed with the
/// state's transforms, the quad lights as unit squares placed on them, and the state's
/// materials; in one flat BVH or as instances (SceneLayout, chosen by the SceneGeometry). Each
/// scene epoch gets its own; one whose objects stand as in an earlier one shares its flat BVH.
/// Read-only once built, safe from many threads.
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

    /// The widest packet of rays this client traces: 16 (rtcOccluded16, rtcIntersect16) where
    /// the CPU has AVX-512 and Embree traces 16 rays natively, else 8. On this project's AMD EPYC
    /// (AVX-512), 16-wide packets of the client's shadow rays ran 1.2x the rays per second of
    /// 8-wide ones (docs/PERFORMANCE.md, section 1). IGI_PACKET_WIDTH=8 (or 16) in the
    /// environment overrides the choice, for measurements; images do not depend on it.
    static constexpr int kMaxPacket = 16;
    int packetWidth() const { return packetWidth_; }
    /// For tests: the width to use from now on (8 or 16).
    void setPacketWidth(int width) { packetWidth_ = width > 8 ? 16 : 8; }

    /// A shadow ray: is anything along origin + t * direction, t in (0, tfar)?
    struct ShadowRay {
        glm::vec3 origin{0.0f};
        glm::vec3 direction{0.0f};
        float tfar = 0;
    };
    /// Up to kMaxPacket shadow rays in one Embree packet (one of packetWidth() where count fits,
    /// else 16): blocked[i] tells whether ray i is blocked. The answer is the single ray's.
    void occludedPacket(const ShadowRay* rays, int count, bool* blocked,
                        RayCounters& counters) const;
    /// The same for N = 8 or 16 rays written in place by their owner (no copy): set lanes
    /// [0, count) with set(), then trace.
    template <int N>
    struct ShadowPacket;
    template <int N>
    void occluded(ShadowPacket<N>& packet, int count, bool* blocked, RayCounters& counters) const;
    /// How much of a hit intersectPacket fills.
    enum class HitDetail {
        Full,      ///< everything, as intersect()
        Emission,  ///< what the hit emits only: its geometry, material and emission texel
                   ///< (no albedo, roughness, vertex colour or normal map: the light-edge rays)
    };
    /// Up to kMaxPacket closest-hit rays in one packet, as intersect() each: found[i] tells
    /// whether ray i hit, and then hits[i] is its hit (only the part `detail` asks for).
    void intersectPacket(const glm::vec3* origins, const glm::vec3* directions, const float* tfar,
                         int count, SurfacePoint* hits, bool* found, RayCounters& counters,
                         HitDetail detail = HitDetail::Full) const;

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
    /// A triangle's uvs at its three corners, as a hit interpolates them (its barycentric
    /// corners (0, 0), (1, 0), (0, 1) when the mesh has none).
    std::array<glm::vec2, 3> triangleUvs(std::uint32_t mesh, std::uint32_t triangle) const;

    const std::vector<Material>& materials() const { return materials_; }
    /// The scene's decoded textures (Material's texture indices point here).
    const std::vector<Texture>& textures() const { return *textures_; }
    const SceneGeometry& geometry() const { return geometry_; }
    /// The unit square onto a quad light: x along edge1, y along edge2, z along its normal.
    static glm::mat4 quadLightMatrix(const QuadLight& q);
    /// How this version is laid out for Embree (SceneLayout).
    SceneLayout layout() const { return layout_; }
    /// The Embree scene every ray is traced in, for benchmarks that trace it directly.
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
    /// The centre of the scene's bounds: with diagonal() / 2 as radius, a sphere around it all
    /// (the disk that light from infinitely far away enters through).
    glm::vec3 center() const { return center_; }
    /// The environment: what a ray that leaves the scene sees besides the suns' disks.
    const EnvironmentMap& environment() const { return environment_; }
    /// The disks of the soft suns that are on (SunDisk), in the state's light order.
    const std::vector<SunDisk>& suns() const { return suns_; }
    /// Whether a ray that leaves the scene may see anything: an environment or a sun's disk.
    bool hasSky() const { return environment().present() || !suns_.empty(); }
    /// What a ray that leaves the scene along `direction` sees, whole: the environment and the
    /// suns' disks (for rays no light sample could stand for: camera rays and mirror chains).
    glm::vec3 skyRadiance(glm::vec3 direction) const {
        glm::vec3 radiance = environment_.radiance(direction);
        if (!suns_.empty()) radiance += sunRadianceToward(suns_, glm::normalize(direction));
        return radiance;
    }
    /// Area-weighted mean Lambertian albedo of the diffuse surfaces (the fraction of light paths
    /// continued at each diffuse bounce in the quasi-random walk).
    float meanAlbedo() const { return meanAlbedo_; }
    std::uint64_t triangleCount() const { return triangleCount_; }

  private:
    struct MeshData {
        const Mesh* mesh = nullptr;
        glm::mat4 objectToWorld{1.0f};
        glm::mat3 normalToWorld{1.0f};
        int material = -1;       ///< every triangle's material, or -1: the mesh's own per triangle
        bool instanced = false;  ///< Mesh::instanced: faceNormals is empty
        /// A glTF file's part (Mesh::partOf): each vertex normal and tangent goes through the
        /// node matrix (localNormal, localLinear) and is normalized, as the loader does when it
        /// flattens; then through the object's (normalToWorld, objectLinear). Else objectToWorld
        /// takes the interpolated ones.
        bool perVertex = false;
        glm::mat3 localLinear{1.0f}, localNormal{1.0f}, objectLinear{1.0f};
        glm::vec3 vertexNormal(std::uint32_t i) const {
            const glm::vec3 n = localNormal * mesh->normals[i];
            const float len = glm::length(n);
            return len > 0.0f && std::isfinite(len) ? n / len : n;
        }
        glm::vec4 vertexTangent(std::uint32_t i) const {
            const glm::vec4 t = mesh->tangents[i];
            if (!perVertex) return t;
            const glm::vec3 d = localLinear * glm::vec3(t);
            const float len = glm::length(d);
            if (!(len > 0.0f) || !std::isfinite(len)) return glm::vec4(0.0f);
            return glm::vec4(d / len, t.w);
        }
        /// Per triangle, the unit geometric normal in world space (0, 0, 1 for a degenerate
        /// one), as fillSurfacePoint gives it: computed once rather than at every hit, from the
        /// world-space vertices (three transforms, a square root and a division).
        std::vector<glm::vec3> faceNormals;
    };
    /// The unit geometric normal of a triangle from its world-space vertices.
    static glm::vec3 faceNormalOf(const WorldTriangle& t);

    /// Adds a mesh's data (and in the instanced layout, its instance) as the next mesh index;
    /// `scene` is its object-space Embree scene, null for a mesh without triangles.
    void addMesh(const Mesh& mesh, RTCScene scene, const glm::mat4& objectToWorld, int material,
                 bool instanced);
    std::uint32_t materialOf(const MeshData& m, std::uint32_t triangle) const {
        return m.material >= 0 ? std::uint32_t(m.material) : m.mesh->materialIds[triangle];
    }
    WorldTriangle worldTriangle(std::uint32_t mesh, std::uint32_t triangle) const;
    /// The hit of a ray that found primitive `prim` of geometry `geom` (instance `inst` when
    /// instanced) at barycentrics (u, v), distance t.
    void fillSurfacePoint(std::uint32_t geom, std::uint32_t inst, std::uint32_t prim, float u,
                          float v, float t, SurfacePoint& hit) const;
    /// What fillTextures needs of a hit besides the SurfacePoint: its mesh, triangle,
    /// barycentrics and unit interpolated normal (not yet turned to the face's side).
    /// (No member initializers: a packet's array of them is filled where a ray hit, and
    /// zeroing it first cost a 768-byte store per packet.)
    struct HitVertices {
        const MeshData* m;
        glm::uvec3 t;
        float u, v;
        glm::vec3 interpolated;
    };
    /// fillSurfacePoint in two halves, for packets (intersectPacket): the geometry (position,
    /// normals, uv, material) first, then what the textures give (albedo, roughness and
    /// metallic, emission, the normal or bump map). Between them prefetchTextures asks the
    /// memory for every hit's texels at once, so that their waits overlap instead of coming
    /// one after another.
    HitVertices fillGeometry(std::uint32_t geom, std::uint32_t inst, std::uint32_t prim, float u,
                             float v, float t, SurfacePoint& hit) const;
    void prefetchTextures(const HitVertices& h, const SurfacePoint& hit) const;
    void fillTextures(const HitVertices& h, SurfacePoint& hit) const;
    /// The emission texel only (HitDetail::Emission).
    void fillEmission(SurfacePoint& hit) const;
    /// Replaces hit.shadingNormal by the normal or bump map's (the material has one, the mesh uvs);
    /// `n` is the unit interpolated normal (or the face's) before it was turned to ng's side.
    void applyNormalMap(const MeshData& m, glm::uvec3 t, float u, float v, glm::vec3 n,
                        SurfacePoint& hit) const;
    std::vector<WorldTriangle> trianglesWhere(
        const std::function<bool(const Material&)>& predicate) const;
    /// The box (lowest, highest corner) around every object's bounds as placed.
    std::pair<glm::vec3, glm::vec3> placedBounds() const;
    void computeMeanAlbedo(const std::vector<Texture>& textures);

    const SceneGeometry& geometry_;
    std::vector<Material> materials_;
    const std::vector<Texture>* textures_ = nullptr;
    std::uint32_t quadLightMaterialBase_ = 0;
    std::uint32_t cutOutBase_ = 0;  ///< flat: the first geometry ID of cut-out triangles
    std::vector<MeshData> meshes_;
    SceneLayout layout_ = SceneLayout::Flat;
    RTCScene top_ = nullptr;
    float diagonal_ = 1.0f;
    glm::vec3 center_{0.0f};
    float meanAlbedo_ = 0.5f;
    EnvironmentMap environment_;  ///< the state's (a live change may differ from the file's)
    std::vector<SunDisk> suns_;
    std::uint64_t triangleCount_ = 0;
    int packetWidth_ = 8;
};

template <int N>
struct TraceableScene::ShadowPacket {
    static_assert(N == 8 || N == 16);
    using Rays = std::conditional_t<N == 8, RTCRay8, RTCRay16>;
    alignas(64) int valid[N];
    alignas(64) Rays rays;

    /// The lanes' fixed fields, once: Embree writes only tfar back (-inf on a hit).
    ShadowPacket() {
        for (int i = 0; i < N; ++i) {
            set(i, glm::vec3(0.0f), glm::vec3(0, 0, 1), 0.0f);
            rays.tnear[i] = 0.0f;
            rays.mask[i] = 0xFFFFFFFFu;
            rays.flags[i] = 0;
            rays.time[i] = 0;
            rays.id[i] = unsigned(i);
        }
    }
    void set(int lane, glm::vec3 origin, glm::vec3 direction, float tfar) {
        rays.org_x[lane] = origin.x;
        rays.org_y[lane] = origin.y;
        rays.org_z[lane] = origin.z;
        rays.dir_x[lane] = direction.x;
        rays.dir_y[lane] = direction.y;
        rays.dir_z[lane] = direction.z;
        rays.tfar[lane] = tfar;
    }
};

template <int N>
void TraceableScene::occluded(ShadowPacket<N>& packet, int count, bool* blocked,
                              RayCounters& counters) const {
    counters.rays += std::uint64_t(count);
    counters.shadowRays += std::uint64_t(count);
    // Lanes past `count` are switched off: Embree reads nothing else of them.
    for (int i = 0; i < N; ++i) packet.valid[i] = i < count ? -1 : 0;
    RTCIntersectContext context;
    // Not RTC_INTERSECT_CONTEXT_FLAG_COHERENT: the client's shadow rays of one packet share an
    // origin or an end, but their directions spread, and with that flag they ran at half the
    // speed of single rays (igi-bench, 1 thread, default scene: 3.0 against 5.7 Mrays/s).
    rtcInitIntersectContext(&context);
    if constexpr (N == 8)
        rtcOccluded8(packet.valid, top_, &context, &packet.rays);
    else
        rtcOccluded16(packet.valid, top_, &context, &packet.rays);
    for (int i = 0; i < count; ++i) blocked[i] = packet.rays.tfar[i] < 0.0f;  // -inf on a hit
}

}  // namespace igi
