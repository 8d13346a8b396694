#include "tracing/TraceableScene.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "materials/BumpMap.h"
#include "materials/NormalMap.h"
#include "math/Color.h"

namespace igi {
namespace {

glm::vec3 transformPoint(const glm::mat4& m, glm::vec3 p) {
    return glm::vec3(m * glm::vec4(p, 1.0f));
}

// Fills lanes [0, count) of an Embree ray packet of width N; the others are switched off.
template <int N, typename Packet>
void fillPacket(Packet& rays, int* valid, int count, const glm::vec3* origins,
                const glm::vec3* directions, const float* tfar) {
    for (int i = 0; i < N; ++i) {
        const bool on = i < count;
        const glm::vec3 o = on ? origins[i] : glm::vec3(0.0f);
        valid[i] = on ? -1 : 0;
        rays.org_x[i] = o.x;
        rays.org_y[i] = o.y;
        rays.org_z[i] = o.z;
        rays.dir_x[i] = on ? directions[i].x : 0.0f;
        rays.dir_y[i] = on ? directions[i].y : 0.0f;
        rays.dir_z[i] = on ? directions[i].z : 1.0f;
        rays.tnear[i] = 0.0f;
        rays.tfar[i] = on ? tfar[i] : 0.0f;
        rays.mask[i] = 0xFFFFFFFFu;
        rays.flags[i] = 0;
        rays.time[i] = 0;
        rays.id[i] = unsigned(i);
    }
}

// An Embree closest-hit packet of width N with its lane mask.
template <int N>
struct HitPacket {
    static constexpr int kWidth = N;
    alignas(64) int valid[N];
    alignas(64) std::conditional_t<N == 8, RTCRayHit8, RTCRayHit16> packet;
};

// Whether every ray leaves from origins[0] with the direction signs of directions[0].
bool sameOriginAndOctant(const glm::vec3* origins, const glm::vec3* directions, int count) {
    for (int i = 1; i < count; ++i) {
        if (origins[i] != origins[0]) return false;
        for (int c = 0; c < 3; ++c)
            if (std::signbit(directions[i][c]) != std::signbit(directions[0][c])) return false;
    }
    return true;
}

int defaultPacketWidth(RTCDevice device) {
    if (const char* forced = std::getenv("IGI_PACKET_WIDTH")) {
        const int w = std::atoi(forced);
        if (w == 8 || w == 16) return w;
    }
    const bool native16 = rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED);
    return native16 && __builtin_cpu_supports("avx512f") ? 16 : 8;
}

}  // namespace

glm::mat4 TraceableScene::quadLightMatrix(const QuadLight& q) {
    const glm::vec3 n = glm::cross(q.edge1, q.edge2);
    const float len = glm::length(n);
    return glm::mat4(glm::vec4(q.edge1, 0), glm::vec4(q.edge2, 0),
                     glm::vec4(len > 0 ? n / len : n, 0), glm::vec4(q.corner, 1));
}

namespace {

Material quadLightMaterial(const QuadLight& q) {
    Material m;
    m.name = q.name.empty() ? "quad light" : q.name;
    m.diffuse = glm::vec3(0.0f);  // a pure emitter: it reflects nothing
    m.emission = q.on ? q.radiance : glm::vec3(0.0f);
    return m;
}

}  // namespace

TraceableScene::TraceableScene(const SceneGeometry& geometry)
    : TraceableScene(geometry, SceneState::of(geometry.scene())) {}

TraceableScene::TraceableScene(const SceneGeometry& geometry, const SceneState& state)
    : geometry_(geometry),
      materials_(state.materials),
      textures_(&geometry.scene().textures),
      environment_(geometry.environmentFor(state.environment)),
      suns_(sunDisksOf(state.punctualLights)) {
    const Scene& scene = geometry.scene();
    quadLightMaterialBase_ = std::uint32_t(materials_.size());
    cutOutBase_ = std::uint32_t(scene.meshes.size() + state.quadLights.size());
    for (const QuadLight& q : state.quadLights) materials_.push_back(quadLightMaterial(q));

    packetWidth_ = defaultPacketWidth(geometry.device().get());
    layout_ = geometry.layoutOf(state);
    if (layout_ == SceneLayout::Instanced) {
        top_ = rtcNewScene(geometry.device().get());
        rtcSetSceneFlags(top_, RTC_SCENE_FLAG_ROBUST);
    }
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
        addMesh(geometryOf(scene, i), geometry.mesh(i), meshToWorld(scene, state.transforms, i),
                scene.meshes[i].material, scene.meshes[i].instanced);
        // A glTF file's part: its vertex normals and tangents through its node matrix one by
        // one, normalized, as the loader flattens them; then its object's transform.
        if (scene.meshes[i].partOf >= 0) {
            MeshData& m = meshes_.back();
            const glm::mat4 object = state.transforms[objectOf(scene, i)].matrix();
            m.perVertex = true;
            m.localLinear = glm::mat3(scene.meshes[i].local);
            m.localNormal = glm::transpose(glm::inverse(m.localLinear));
            m.objectLinear = glm::mat3(object);
            m.normalToWorld = glm::transpose(glm::inverse(m.objectLinear));
        }
    }
    for (std::size_t i = 0; i < state.quadLights.size(); ++i)
        addMesh(geometry.unitQuad(), geometry.unitQuadScene(), quadLightMatrix(state.quadLights[i]),
                int(quadLightMaterialBase_ + i), false);
    if (layout_ == SceneLayout::Instanced)
        rtcCommitScene(top_);
    else
        top_ = geometry.flatScene(state);

    const auto [lo, hi] = placedBounds();
    const float d = glm::length(hi - lo);
    diagonal_ = std::isfinite(d) && d > 0 ? d : 1.0f;
    center_ = std::isfinite(d) ? 0.5f * (lo + hi) : glm::vec3(0.0f);
    computeMeanAlbedo(scene.textures);
}

std::pair<glm::vec3, glm::vec3> TraceableScene::placedBounds() const {
    // Each object's own bounds placed by its transform (the box around their eight placed
    // corners), as Embree bounds an instance: the same in both layouts, so the scale and
    // everything set relative to it (ray offsets, the clamp) do not depend on the layout.
    glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-lo);
    for (std::size_t i = 0; i < meshes_.size(); ++i) {
        const MeshData& m = meshes_[i];
        const RTCScene object =
            i < geometry_.scene().meshes.size() ? geometry_.mesh(i) : geometry_.unitQuadScene();
        if (!object) continue;
        RTCBounds b;
        rtcGetSceneBounds(object, &b);
        for (int c = 0; c < 8; ++c) {
            const glm::vec3 corner(c & 1 ? b.upper_x : b.lower_x, c & 2 ? b.upper_y : b.lower_y,
                                   c & 4 ? b.upper_z : b.lower_z);
            const glm::vec3 p = transformPoint(m.objectToWorld, corner);
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
    }
    return {lo, hi};
}

TraceableScene::~TraceableScene() {
    if (top_) rtcReleaseScene(top_);
}

void TraceableScene::addMesh(const Mesh& mesh, RTCScene scene, const glm::mat4& objectToWorld,
                             int material, bool instanced) {
    MeshData data;
    data.mesh = &mesh;
    data.objectToWorld = objectToWorld;
    data.normalToWorld = glm::transpose(glm::inverse(glm::mat3(objectToWorld)));
    data.material = material;
    data.instanced = instanced;
    const auto id = std::uint32_t(meshes_.size());
    meshes_.push_back(data);  // worldTriangle reads it
    MeshData& added = meshes_.back();
    // An instance's face normals are computed at each hit: stored, they would be a world-space
    // copy of its geometry per instance, what instancing saves.
    if (!instanced) {
        added.faceNormals.resize(mesh.triangles.size());
        for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t)
            added.faceNormals[t] = faceNormalOf(worldTriangle(id, t));
    }
    if (scene) {
        // Flat: the geometry's own scene has it already, under the same ID.
        if (layout_ == SceneLayout::Instanced)
            geometry_.attachInstance(top_, scene, data.objectToWorld, id);
        triangleCount_ += mesh.triangles.size();
    }
}

glm::vec3 TraceableScene::faceNormalOf(const WorldTriangle& t) {
    const glm::vec3 ng = glm::cross(t.p1 - t.p0, t.p2 - t.p0);
    const float len = glm::length(ng);
    return len > 0 ? ng / len : glm::vec3(0, 0, 1);
}

bool TraceableScene::intersect(glm::vec3 origin, glm::vec3 direction, float tfar, SurfacePoint& hit,
                               RayCounters& counters) const {
    ++counters.rays;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh;
    rh.ray.org_x = origin.x;
    rh.ray.org_y = origin.y;
    rh.ray.org_z = origin.z;
    rh.ray.dir_x = direction.x;
    rh.ray.dir_y = direction.y;
    rh.ray.dir_z = direction.z;
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = tfar;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.flags = 0;
    rh.ray.time = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(top_, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    fillSurfacePoint(rh.hit.geomID, rh.hit.instID[0], rh.hit.primID, rh.hit.u, rh.hit.v,
                     rh.ray.tfar, hit);
    return true;
}

bool TraceableScene::occludedIn(RTCScene scene, glm::vec3 origin, glm::vec3 direction, float tfar,
                                RayCounters& counters) {
    ++counters.rays;
    ++counters.shadowRays;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray;
    ray.org_x = origin.x;
    ray.org_y = origin.y;
    ray.org_z = origin.z;
    ray.dir_x = direction.x;
    ray.dir_y = direction.y;
    ray.dir_z = direction.z;
    ray.tnear = 0.0f;
    ray.tfar = tfar;
    ray.mask = 0xFFFFFFFFu;
    ray.flags = 0;
    ray.time = 0;
    rtcOccluded1(scene, &context, &ray);
    return ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

void TraceableScene::occludedPacket(const ShadowRay* rays, int count, bool* blocked,
                                    RayCounters& counters) const {
    auto trace = [&](auto& packet) {
        for (int i = 0; i < count; ++i)
            packet.set(i, rays[i].origin, rays[i].direction, rays[i].tfar);
        occluded(packet, count, blocked, counters);
    };
    if (count <= 8 && packetWidth_ == 8) {
        ShadowPacket<8> packet;
        trace(packet);
    } else {
        ShadowPacket<16> packet;
        trace(packet);
    }
}

void TraceableScene::intersectPacket(const glm::vec3* origins, const glm::vec3* directions,
                                     const float* tfar, int count, SurfacePoint* hits, bool* found,
                                     RayCounters& counters, HitDetail detail) const {
    counters.rays += std::uint64_t(count);
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    // Eye rays share their origin and, but for the packets that straddle the view's axes, the
    // signs of their directions: for such packets Embree's coherent traversal is 5-6 % faster
    // a frame (igi-bench, Cornell scenes). With directions in other octants it returned wrong
    // hits (TraceableScene_test), so other packets go the usual way.
    if (sameOriginAndOctant(origins, directions, count))
        context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    auto trace = [&](auto& p) {
        constexpr int N = std::remove_reference_t<decltype(p)>::kWidth;
        fillPacket<N>(p.packet.ray, p.valid, count, origins, directions, tfar);
        for (int i = 0; i < N; ++i)
            p.packet.hit.geomID[i] = p.packet.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
        if constexpr (N == 8)
            rtcIntersect8(p.valid, top_, &context, &p.packet);
        else
            rtcIntersect16(p.valid, top_, &context, &p.packet);
        const auto& hit = p.packet.hit;
        for (int i = 0; i < count; ++i) found[i] = hit.geomID[i] != RTC_INVALID_GEOMETRY_ID;
        // A scene without textures has nothing to ask the memory for: one pass, without the
        // halves' vertex records (the Cornell scenes' first frame, docs/MATERIALS.md).
        if (textures_->empty()) {
            for (int i = 0; i < count; ++i)
                if (found[i])
                    fillSurfacePoint(hit.geomID[i], hit.instID[0][i], hit.primID[i], hit.u[i],
                                     hit.v[i], p.packet.ray.tfar[i], hits[i]);
            return;
        }
        if (detail == HitDetail::Emission) {
            // What a hit sends needs no albedo and no normal map: the light-edge rays' hits
            // (most of their cost was the normal map's texels, in the Sponza arcades).
            for (int i = 0; i < count; ++i)
                if (found[i]) {
                    fillGeometry(hit.geomID[i], hit.instID[0][i], hit.primID[i], hit.u[i], hit.v[i],
                                 p.packet.ray.tfar[i], hits[i]);
                    fillEmission(hits[i]);
                }
            return;
        }
        HitVertices vertices[N];
        for (int i = 0; i < count; ++i)
            if (found[i])
                vertices[i] = fillGeometry(hit.geomID[i], hit.instID[0][i], hit.primID[i], hit.u[i],
                                           hit.v[i], p.packet.ray.tfar[i], hits[i]);
        for (int i = 0; i < count; ++i)
            if (found[i]) prefetchTextures(vertices[i], hits[i]);
        for (int i = 0; i < count; ++i)
            if (found[i]) fillTextures(vertices[i], hits[i]);
    };
    if (count <= 8 && packetWidth_ == 8) {
        HitPacket<8> p;
        trace(p);
    } else {
        HitPacket<16> p;
        trace(p);
    }
}

TraceableScene::WorldTriangle TraceableScene::worldTriangle(std::uint32_t mesh,
                                                            std::uint32_t triangle) const {
    const MeshData& m = meshes_[mesh];
    const glm::uvec3 t = m.mesh->triangles[triangle];
    return {transformPoint(m.objectToWorld, m.mesh->positions[t.x]),
            transformPoint(m.objectToWorld, m.mesh->positions[t.y]),
            transformPoint(m.objectToWorld, m.mesh->positions[t.z]),
            materialOf(m, triangle),
            mesh,
            triangle};
}

void TraceableScene::fillSurfacePoint(std::uint32_t geom, std::uint32_t inst, std::uint32_t prim,
                                      float u, float v, float distance, SurfacePoint& hit) const {
    fillTextures(fillGeometry(geom, inst, prim, u, v, distance, hit), hit);
}

// fillGeometry and fillTextures are inlined where they are called, here only: a hit's fill
// through two calls and a returned HitVertices cost the default scene's first frame 0.7 % of
// its instructions (callgrind, docs/MATERIALS.md).
[[gnu::always_inline]] inline TraceableScene::HitVertices TraceableScene::fillGeometry(
    std::uint32_t geom, std::uint32_t inst, std::uint32_t prim, float u, float v, float distance,
    SurfacePoint& hit) const {
    // Through an instance (every mesh in the instanced layout, the instanced meshes in the flat
    // one), the instance's ID is the mesh's; else the geometry ID is.
    const bool viaInstance = inst != RTC_INVALID_GEOMETRY_ID;
    std::uint32_t meshIndex = viaInstance ? inst : geom;
    if (geometry_.anyCutOuts()) {
        // Cut-out triangles are geometry of their own (SceneGeometry): flat, after the meshes
        // and quad lights; through an instance, kCutOutGeometry in the mesh's scene. Either
        // way the primitive is an index into that part's triangles.
        bool cutOut = false;
        if (!viaInstance && geom >= cutOutBase_) {
            meshIndex = geometry_.cutOutMeshes()[geom - cutOutBase_];
            cutOut = true;
        } else if (viaInstance) {
            cutOut = geom == SceneGeometry::kCutOutGeometry;
        }
        if (geometry_.hasCutOuts(meshIndex)) prim = geometry_.meshTriangle(meshIndex, cutOut, prim);
    }
    const MeshData& m = meshes_[meshIndex];
    const Mesh& mesh = *m.mesh;
    const glm::uvec3 t = mesh.triangles[prim];
    const float w = 1.0f - u - v;

    // Interpolating the vertices is more precise than origin + t * direction far from the origin.
    const glm::vec3 pObject =
        w * mesh.positions[t.x] + u * mesh.positions[t.y] + v * mesh.positions[t.z];
    hit.position = transformPoint(m.objectToWorld, pObject);
    const glm::vec3 ng =
        m.instanced ? faceNormalOf(worldTriangle(meshIndex, prim)) : m.faceNormals[prim];
    hit.geometricNormal = ng;

    hit.shadingNormal = ng;
    glm::vec3 interpolated = ng;  // unit, not yet turned to ng's side: a normal map's frame
    if (!mesh.normals.empty()) {
        const glm::vec3 nObject =
            m.perVertex
                ? w * m.vertexNormal(t.x) + u * m.vertexNormal(t.y) + v * m.vertexNormal(t.z)
                : w * mesh.normals[t.x] + u * mesh.normals[t.y] + v * mesh.normals[t.z];
        const glm::vec3 ns = m.normalToWorld * nObject;
        const float nsLen = glm::length(ns);
        if (nsLen > 0 && std::isfinite(nsLen)) {
            hit.shadingNormal = glm::dot(ns, ng) < 0 ? -ns / nsLen : ns / nsLen;
            interpolated = ns / nsLen;
        }
    }
    hit.uv = mesh.uvs.empty() ? glm::vec2(u, v)
                              : w * mesh.uvs[t.x] + u * mesh.uvs[t.y] + v * mesh.uvs[t.z];
    hit.mesh = meshIndex;
    hit.triangle = prim;
    hit.distance = distance;
    hit.material = &materials_[materialOf(m, prim)];
    return {&m, t, u, v, interpolated};
}

void TraceableScene::prefetchTextures(const HitVertices& h, const SurfacePoint& hit) const {
    const Material& mat = *hit.material;
    const std::vector<Texture>& textures = *textures_;
    if (mat.diffuseTexture >= 0) textures[mat.diffuseTexture].prefetch(mat.diffuseUv(hit.uv));
    if (mat.reflection == Reflection::Ggx && mat.metallicRoughnessTexture >= 0)
        textures[mat.metallicRoughnessTexture].prefetch(mat.metallicRoughnessUv(hit.uv));
    if (mat.emissionTexture >= 0) textures[mat.emissionTexture].prefetch(mat.emissionUv(hit.uv));
    if (mat.perturbsNormal() && !h.m->mesh->uvs.empty()) {
        if (mat.normalTexture >= 0)
            textures[mat.normalTexture].prefetch(mat.normalUv(hit.uv));
        else
            textures[mat.bumpTexture].prefetch(hit.uv);
    }
}

[[gnu::always_inline]] inline void TraceableScene::fillTextures(const HitVertices& h,
                                                                SurfacePoint& hit) const {
    const MeshData& m = *h.m;
    const Mesh& mesh = *m.mesh;
    const glm::uvec3 t = h.t;
    const float u = h.u, v = h.v;
    const float w = 1.0f - u - v;
    hit.albedo = hit.material->diffuse;
    if (hit.material->diffuseTexture >= 0)
        hit.albedo *=
            (*textures_)[hit.material->diffuseTexture].sample(hit.material->diffuseUv(hit.uv));
    if (hit.material->reflection == Reflection::Ggx) {
        hit.roughness = hit.material->roughness;
        hit.metallic = hit.material->metallic;
        if (hit.material->metallicRoughnessTexture >= 0) {
            const glm::vec3 t = (*textures_)[hit.material->metallicRoughnessTexture].sample(
                hit.material->metallicRoughnessUv(hit.uv));
            hit.roughness *= t.y;
            hit.metallic *= t.z;
        }
    }
    if (!mesh.colors.empty())  // glTF COLOR_0: base colour x texture x vertex colour
        hit.albedo *= w * mesh.colors[t.x] + u * mesh.colors[t.y] + v * mesh.colors[t.z];
    fillEmission(hit);
    if (hit.material->perturbsNormal() && !mesh.uvs.empty())
        applyNormalMap(m, t, u, v, h.interpolated, hit);
}

[[gnu::always_inline]] inline void TraceableScene::fillEmission(SurfacePoint& hit) const {
    hit.emissionTexel =
        hit.material->emissionTexture >= 0
            ? (*textures_)[hit.material->emissionTexture].sample(hit.material->emissionUv(hit.uv))
            : glm::vec3(1.0f);
}

void TraceableScene::applyNormalMap(const MeshData& m, glm::uvec3 t, float u, float v, glm::vec3 n,
                                    SurfacePoint& hit) const {
    const Mesh& mesh = *m.mesh;
    const float w = 1.0f - u - v;
    const glm::mat3 toWorld = m.perVertex ? m.objectLinear : glm::mat3(m.objectToWorld);
    normalmap::TangentFrame frame;
    bool framed = false;
    // The vertices' TANGENT when all three have one ((0, 0, 0, 0) where the file gave none).
    if (!mesh.tangents.empty()) {
        const glm::vec4 ta = m.vertexTangent(t.x), tb = m.vertexTangent(t.y),
                        tc = m.vertexTangent(t.z);
        if (ta.w != 0 && tb.w != 0 && tc.w != 0) {
            const glm::vec4 ti = w * ta + u * tb + v * tc;
            // A mirroring placement turns the bitangent's sign, as the loader's matrix does.
            float sign = ti.w < 0 ? -1.0f : 1.0f;
            if (glm::determinant(toWorld) < 0) sign = -sign;
            framed = normalmap::frameFromTangent(n, toWorld * glm::vec3(ti), sign, frame);
            // A transformed map's +u and +v run elsewhere on the surface: d p / d uv' is the
            // frame times the inverse of the transform's linear part.
            const UvTransform& uvt = hit.material->normalUv;
            if (framed && uvt.active) framed = normalmap::transformFrame(uvt.linear, frame);
        }
    }
    // Else the triangle's uv derivatives: not MikkTSpace (NormalMap.h, frameFromUvs).
    if (!framed) {
        const glm::vec3 p[3] = {transformPoint(m.objectToWorld, mesh.positions[t.x]),
                                transformPoint(m.objectToWorld, mesh.positions[t.y]),
                                transformPoint(m.objectToWorld, mesh.positions[t.z])};
        const UvTransform& uvt = hit.material->normalUv;
        const glm::vec2 uv[3] = {uvt(mesh.uvs[t.x]), uvt(mesh.uvs[t.y]), uvt(mesh.uvs[t.z])};
        framed = normalmap::frameFromUvs(n, p, uv, frame);
    }
    if (!framed) return;  // degenerate: the interpolated normal
    const Material& mat = *hit.material;
    // A normal map's texel, or a height map's slope (MTL bump; MTL has no uv transforms).
    const glm::vec3 local =
        mat.normalTexture >= 0
            ? normalmap::tangentSpaceNormal(
                  (*textures_)[mat.normalTexture].sample(mat.normalUv(hit.uv)), mat.normalScale)
            : bumpmap::tangentSpaceNormal((*textures_)[mat.bumpTexture], hit.uv, mat.bumpScale);
    glm::vec3 mapped = normalmap::perturb(n, frame, local);
    const glm::vec3 ng = hit.geometricNormal;
    // Turned to ng's side with the interpolated normal; a map that tilts it below the
    // geometric surface is mirrored in that surface (the view's own check is in lobesAt).
    if (glm::dot(n, ng) < 0) mapped = -mapped;
    const float below = glm::dot(mapped, ng);
    if (below < 0) mapped -= 2.0f * below * ng;
    const float len = glm::length(mapped);
    if (len > 0 && std::isfinite(len)) hit.shadingNormal = mapped / len;
}

std::array<glm::vec2, 3> TraceableScene::triangleUvs(std::uint32_t mesh,
                                                     std::uint32_t triangle) const {
    const Mesh& m = *meshes_[mesh].mesh;
    if (m.uvs.empty()) return {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(0, 1)};
    const glm::uvec3 t = m.triangles[triangle];
    return {m.uvs[t.x], m.uvs[t.y], m.uvs[t.z]};
}

std::vector<TraceableScene::WorldTriangle> TraceableScene::trianglesWhere(
    const std::function<bool(const Material&)>& predicate) const {
    std::vector<WorldTriangle> result;
    for (std::uint32_t mi = 0; mi < meshes_.size(); ++mi) {
        const Mesh& mesh = *meshes_[mi].mesh;
        for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t)
            if (predicate(materials_[materialOf(meshes_[mi], t)]))
                result.push_back(worldTriangle(mi, t));
    }
    return result;
}

std::vector<TraceableScene::WorldTriangle> TraceableScene::triangles() const {
    return trianglesWhere([](const Material&) { return true; });
}

std::vector<TraceableScene::WorldTriangle> TraceableScene::emissiveTriangles() const {
    return trianglesWhere([](const Material& m) { return m.isEmissive(); });
}

std::vector<TraceableScene::WorldTriangle> TraceableScene::specularTriangles() const {
    // A GGX material whose roughness map reaches under the mirror threshold somewhere has
    // mirror texels (they take the mirror path): its triangles are caustic targets too, or
    // the light those texels focus would have no photons.
    return trianglesWhere([this](const Material& m) {
        if (m.isSpecular()) return true;
        if (m.reflection != Reflection::Ggx || m.metallicRoughnessTexture < 0 || !textures_ ||
            std::size_t(m.metallicRoughnessTexture) >= textures_->size())
            return false;
        const float least =
            m.roughness *
            std::clamp((*textures_)[m.metallicRoughnessTexture].minimum.y, 0.0f, 1.0f);
        return least * least < kMinGgxAlpha;
    });
}

void TraceableScene::computeMeanAlbedo(const std::vector<Texture>& textures) {
    double weighted = 0, area = 0;
    for (std::uint32_t mi = 0; mi < meshes_.size(); ++mi) {
        const Mesh& mesh = *meshes_[mi].mesh;
        for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
            const Material& mat = materials_[materialOf(meshes_[mi], t)];
            if (mat.glass) continue;
            glm::vec3 albedo = mat.diffuse;
            if (mat.diffuseTexture >= 0) albedo *= textures[mat.diffuseTexture].average;
            if (!mesh.colors.empty()) {
                const glm::uvec3 c = mesh.triangles[t];
                albedo *= (mesh.colors[c.x] + mesh.colors[c.y] + mesh.colors[c.z]) / 3.0f;
            }
            if (isBlack(albedo)) continue;
            const WorldTriangle w = worldTriangle(mi, t);
            const double a = 0.5 * glm::length(glm::cross(w.p1 - w.p0, w.p2 - w.p0));
            if (!std::isfinite(a)) continue;
            weighted += a * meanComponent(albedo);
            area += a;
        }
    }
    // Bounded away from 0 and 1: it is a continuation fraction and a divisor.
    meanAlbedo_ = area > 0 ? float(std::clamp(weighted / area, 0.05, 0.95)) : 0.5f;
}

}  // namespace igi
