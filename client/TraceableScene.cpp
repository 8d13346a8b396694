#include "TraceableScene.h"

#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "math/Color.h"

namespace igi {
namespace {

glm::vec3 transformPoint(const glm::mat4& m, glm::vec3 p) {
    return glm::vec3(m * glm::vec4(p, 1.0f));
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
    : geometry_(geometry), materials_(state.materials), textures_(&geometry.scene().textures) {
    const Scene& scene = geometry.scene();
    quadLightMaterialBase_ = std::uint32_t(materials_.size());
    for (const QuadLight& q : state.quadLights) materials_.push_back(quadLightMaterial(q));

    top_ = rtcNewScene(geometry.device().get());
    rtcSetSceneFlags(top_, RTC_SCENE_FLAG_ROBUST);
    for (std::size_t i = 0; i < scene.meshes.size(); ++i)
        addInstance(scene.meshes[i], geometry.mesh(i), state.transforms[i].matrix(), -1);
    for (std::size_t i = 0; i < state.quadLights.size(); ++i)
        addInstance(geometry.unitQuad(), geometry.unitQuadScene(),
                    quadLightMatrix(state.quadLights[i]), int(quadLightMaterialBase_ + i));
    rtcCommitScene(top_);

    RTCBounds b;
    rtcGetSceneBounds(top_, &b);
    const glm::vec3 extent(b.upper_x - b.lower_x, b.upper_y - b.lower_y, b.upper_z - b.lower_z);
    const float d = glm::length(extent);
    diagonal_ = std::isfinite(d) && d > 0 ? d : 1.0f;
    computeMeanAlbedo(scene.textures);
}

TraceableScene::~TraceableScene() {
    if (top_) rtcReleaseScene(top_);
}

void TraceableScene::addInstance(const Mesh& mesh, RTCScene scene, const glm::mat4& objectToWorld,
                                 int material) {
    MeshData data;
    data.mesh = &mesh;
    data.objectToWorld = objectToWorld;
    data.normalToWorld = glm::transpose(glm::inverse(glm::mat3(objectToWorld)));
    data.material = material;
    const auto id = std::uint32_t(meshes_.size());
    if (scene) {
        RTCGeometry instance = rtcNewGeometry(geometry_.device().get(), RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(instance, scene);
        rtcSetGeometryTransform(instance, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR,
                                glm::value_ptr(data.objectToWorld));
        rtcCommitGeometry(instance);
        rtcAttachGeometryByID(top_, instance, id);
        rtcReleaseGeometry(instance);
        triangleCount_ += mesh.triangles.size();
    }
    meshes_.push_back(data);
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
    fillSurfacePoint(rh, hit);
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

void TraceableScene::occluded8(glm::vec3 origin, const glm::vec3* directions, const float* tfar,
                               int count, bool* blocked, RayCounters& counters) const {
    counters.rays += std::uint64_t(count);
    counters.shadowRays += std::uint64_t(count);
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    // Not RTC_INTERSECT_CONTEXT_FLAG_COHERENT, though the rays share their origin: their
    // directions spread over the hemisphere, and with that flag the client's shadow rays ran
    // at half the speed of single rays (igi-bench, 1 thread, default scene: 3.0 against 5.7
    // Mrays/s); without it, 1.4x faster than single rays.
    alignas(32) int valid[kPacket];
    alignas(32) RTCRay8 rays;
    for (int i = 0; i < kPacket; ++i) {
        const bool on = i < count;
        valid[i] = on ? -1 : 0;
        rays.org_x[i] = origin.x;
        rays.org_y[i] = origin.y;
        rays.org_z[i] = origin.z;
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
    rtcOccluded8(valid, top_, &context, &rays);
    for (int i = 0; i < count; ++i) blocked[i] = rays.tfar[i] < 0.0f;  // -inf on a hit
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

void TraceableScene::fillSurfacePoint(const RTCRayHit& rh, SurfacePoint& hit) const {
    const std::uint32_t meshIndex = rh.hit.instID[0];
    const MeshData& m = meshes_[meshIndex];
    const Mesh& mesh = *m.mesh;
    const glm::uvec3 t = mesh.triangles[rh.hit.primID];
    const float u = rh.hit.u, v = rh.hit.v, w = 1.0f - u - v;

    // Interpolating the vertices is more precise than origin + t * direction far from the origin.
    const glm::vec3 pObject =
        w * mesh.positions[t.x] + u * mesh.positions[t.y] + v * mesh.positions[t.z];
    hit.position = transformPoint(m.objectToWorld, pObject);
    const WorldTriangle tri = worldTriangle(meshIndex, rh.hit.primID);
    glm::vec3 ng = glm::cross(tri.p1 - tri.p0, tri.p2 - tri.p0);
    const float len = glm::length(ng);
    ng = len > 0 ? ng / len : glm::vec3(0, 0, 1);
    hit.geometricNormal = ng;

    hit.shadingNormal = ng;
    if (!mesh.normals.empty()) {
        const glm::vec3 nObject =
            w * mesh.normals[t.x] + u * mesh.normals[t.y] + v * mesh.normals[t.z];
        const glm::vec3 ns = m.normalToWorld * nObject;
        const float nsLen = glm::length(ns);
        if (nsLen > 0 && std::isfinite(nsLen))
            hit.shadingNormal = glm::dot(ns, ng) < 0 ? -ns / nsLen : ns / nsLen;
    }
    hit.uv = mesh.uvs.empty() ? glm::vec2(u, v)
                              : w * mesh.uvs[t.x] + u * mesh.uvs[t.y] + v * mesh.uvs[t.z];
    hit.mesh = meshIndex;
    hit.triangle = rh.hit.primID;
    hit.distance = rh.ray.tfar;
    hit.material = &materials_[materialOf(m, rh.hit.primID)];
    hit.albedo = hit.material->diffuse;
    if (hit.material->diffuseTexture >= 0)
        hit.albedo *= (*textures_)[hit.material->diffuseTexture].sample(hit.uv);
}

std::vector<TraceableScene::WorldTriangle> TraceableScene::trianglesWhere(
    bool (*predicate)(const Material&)) const {
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
    return trianglesWhere([](const Material& m) { return m.isSpecular(); });
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
