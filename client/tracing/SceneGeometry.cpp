#include "tracing/SceneGeometry.h"

#include <map>
#include <stdexcept>
#include <utility>

#include <glm/gtc/type_ptr.hpp>

#include "tracing/TraceableScene.h"

namespace igi {

/// A committed flat Embree scene and the placement it was built for; the cache holds one
/// reference, every version that uses it another.
struct SceneGeometry::FlatScene {
    Placement placement;
    RTCScene scene = nullptr;
    ~FlatScene() {
        if (scene) rtcReleaseScene(scene);
    }
};

SceneGeometry::SceneGeometry(const EmbreeDevice& device, const Scene& scene)
    : device_(device), scene_(scene), environment_(scene.environment, scene.textures) {
    splitByCoverage();
    // Instances of one geometry share its scene: one per geometry, or per geometry and
    // material where the material cuts out (the split of its triangles depends on it).
    std::map<std::pair<std::size_t, std::int32_t>, RTCScene> shared;
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
        const Mesh& mesh = geometryOf(scene, i);
        triangleCount_ += mesh.triangles.size();
        if (mesh.triangles.empty()) {
            meshes_.push_back(nullptr);
            continue;
        }
        if (!scene.meshes[i].instanced) {
            meshes_.push_back(build(mesh, &parts_[i]));
            builtTriangles_ += mesh.triangles.size();
            continue;
        }
        const std::size_t holder = &mesh - scene.meshes.data();
        const std::pair key{holder, parts_[i].cutOut ? scene.meshes[i].material : -1};
        auto it = shared.find(key);
        if (it == shared.end()) {
            it = shared.emplace(key, build(mesh, &parts_[i])).first;
            builtTriangles_ += mesh.triangles.size();
        } else {
            rtcRetainScene(it->second);  // each slot of meshes_ holds a reference
        }
        meshes_.push_back(it->second);
        anyInstanced_ = true;
    }
    instancedScenes_ = shared.size();
    unitQuad_.name = "unit quad";
    unitQuad_.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    unitQuad_.triangles = {{0, 1, 2}, {0, 2, 3}};
    unitQuad_.materialIds = {0, 0};  // each quad light instance says which material it uses
    unitQuadScene_ = build(unitQuad_, nullptr);
    loaded_ = placementOf(SceneState::of(scene));
}

SceneGeometry::~SceneGeometry() {
    for (RTCScene s : meshes_)
        if (s) rtcReleaseScene(s);
    if (unitQuadScene_) rtcReleaseScene(unitQuadScene_);
}

namespace {

// Embree reads the triangles' vertices as given: one float transform per vertex, the same for
// the flat scene and for MovedInstances, so that both find the same hits.
glm::vec3 toWorld(const glm::mat4& m, glm::vec3 p) {
    return glm::vec3(m * glm::vec4(p, 1.0f));
}

// The mesh's triangles, or only those listed in `subset` (in its order: primitive i is
// triangle subset[i]); a cut-out subset gets the coverage filter functions.
RTCGeometry newTriangles(RTCDevice device, const Mesh& mesh, const glm::mat4* objectToWorld,
                         const std::vector<std::uint32_t>* subset = nullptr,
                         const CutOutTriangles* cutOut = nullptr) {
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    const std::size_t count = subset ? subset->size() : mesh.triangles.size();
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), mesh.positions.size()));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), count));
    if (!vertices || !indices) {
        rtcReleaseGeometry(geom);
        throw std::runtime_error("Embree could not allocate the buffers of mesh " + mesh.name);
    }
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const glm::vec3 p =
            objectToWorld ? toWorld(*objectToWorld, mesh.positions[i]) : mesh.positions[i];
        for (int c = 0; c < 3; ++c) vertices[3 * i + c] = p[c];
    }
    for (std::size_t i = 0; i < count; ++i)
        for (int c = 0; c < 3; ++c)
            indices[3 * i + c] = mesh.triangles[subset ? (*subset)[i] : i][c];
    if (cutOut) {
        rtcSetGeometryUserData(geom, const_cast<CutOutTriangles*>(cutOut));
        rtcSetGeometryIntersectFilterFunction(geom, coverageFilter);
        rtcSetGeometryOccludedFilterFunction(geom, coverageFilter);
    }
    rtcCommitGeometry(geom);
    return geom;
}

}  // namespace

void SceneGeometry::splitByCoverage() {
    std::vector<bool> cutOutMaterial(scene_.materials.size());
    bool any = false;
    for (std::size_t i = 0; i < scene_.materials.size(); ++i) {
        cutOutMaterial[i] = igi::hasCutOuts(scene_.materials[i], scene_.textures);
        any = any || cutOutMaterial[i];
    }
    parts_.resize(scene_.meshes.size());
    if (!any) return;  // every mesh as before: one geometry, primitive = triangle
    for (std::size_t i = 0; i < scene_.meshes.size(); ++i) {
        const Mesh& mesh = geometryOf(scene_, i);
        const std::int32_t uniform = scene_.meshes[i].material;
        auto cutOut = std::make_unique<CutOutTriangles>();
        std::vector<std::uint32_t> opaque;
        for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
            const std::uint32_t material = uniform >= 0                  ? std::uint32_t(uniform)
                                           : t < mesh.materialIds.size() ? mesh.materialIds[t]
                                                                         : 0;
            if (material < cutOutMaterial.size() && cutOutMaterial[material])
                cutOut->triangles.push_back(t);
            else
                opaque.push_back(t);
        }
        if (cutOut->triangles.empty()) continue;
        cutOut->mesh = &mesh;
        cutOut->meshIndex = std::uint32_t(i);
        cutOut->material = uniform;
        cutOut->materials = &scene_.materials;
        cutOut->textures = &scene_.textures;
        parts_[i].opaque = std::move(opaque);
        parts_[i].cutOut = std::move(cutOut);
        anyCutOuts_ = true;
        // An instance's cut-out triangles are in its geometry's scene, not the flat one.
        if (!scene_.meshes[i].instanced) cutOutMeshes_.push_back(std::uint32_t(i));
    }
}

RTCScene SceneGeometry::build(const Mesh& mesh, const Parts* parts) const {
    RTCScene scene = rtcNewScene(device_.get());
    // Robust traversal: no hit is lost on shared edges, so closed meshes do not leak light.
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    if (parts && parts->cutOut) {
        if (!parts->opaque.empty()) {
            RTCGeometry geom = newTriangles(device_.get(), mesh, nullptr, &parts->opaque);
            rtcAttachGeometryByID(scene, geom, kOpaqueGeometry);
            rtcReleaseGeometry(geom);
        }
        RTCGeometry geom = newTriangles(device_.get(), mesh, nullptr, &parts->cutOut->triangles,
                                        parts->cutOut.get());
        rtcAttachGeometryByID(scene, geom, kCutOutGeometry);
        rtcReleaseGeometry(geom);
    } else {
        RTCGeometry geom = newTriangles(device_.get(), mesh, nullptr);
        rtcAttachGeometry(scene, geom);
        rtcReleaseGeometry(geom);
    }
    rtcCommitScene(scene);
    return scene;
}

void SceneGeometry::attachWorldMesh(RTCScene scene, const Mesh& mesh,
                                    const glm::mat4& objectToWorld, std::uint32_t id) const {
    RTCGeometry geom = newTriangles(device_.get(), mesh, &objectToWorld);
    rtcAttachGeometryByID(scene, geom, id);
    rtcReleaseGeometry(geom);
}

void SceneGeometry::attachWorldMesh(RTCScene scene, std::size_t mesh,
                                    const glm::mat4& objectToWorld, std::uint32_t id,
                                    std::uint32_t cutOutId) const {
    if (scene_.meshes[mesh].instanced) {  // one BVH for all instances of its geometry
        if (meshes_[mesh]) attachInstance(scene, meshes_[mesh], objectToWorld, id);
        return;
    }
    const Parts& parts = parts_[mesh];
    if (!parts.cutOut) {
        attachWorldMesh(scene, scene_.meshes[mesh], objectToWorld, id);
        return;
    }
    const Mesh& m = scene_.meshes[mesh];  // not an instance: its own geometry
    if (!parts.opaque.empty()) {
        RTCGeometry geom = newTriangles(device_.get(), m, &objectToWorld, &parts.opaque);
        rtcAttachGeometryByID(scene, geom, id);
        rtcReleaseGeometry(geom);
    }
    RTCGeometry geom = newTriangles(device_.get(), m, &objectToWorld, &parts.cutOut->triangles,
                                    parts.cutOut.get());
    rtcAttachGeometryByID(scene, geom, cutOutId);
    rtcReleaseGeometry(geom);
}

void SceneGeometry::attachInstance(RTCScene scene, RTCScene object, const glm::mat4& objectToWorld,
                                   std::uint32_t id) const {
    RTCGeometry instance = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(instance, object);
    rtcSetGeometryTransform(instance, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR,
                            glm::value_ptr(objectToWorld));
    rtcCommitGeometry(instance);
    rtcAttachGeometryByID(scene, instance, id);
    rtcReleaseGeometry(instance);
}

SceneGeometry::Placement SceneGeometry::placementOf(const SceneState& state) const {
    Placement p;
    for (std::size_t i = 0; i < state.transforms.size(); ++i)
        p.meshes.push_back(meshToWorld(scene_, state.transforms, i));
    for (const QuadLight& q : state.quadLights)
        p.quadLights.push_back(TraceableScene::quadLightMatrix(q));
    return p;
}

EnvironmentMap SceneGeometry::environmentFor(const Environment& environment) const {
    if (environment == environment_.description()) return environment_;
    // A camera that moves after a change of the sky makes an epoch per frame with the same
    // environment: its tables (a map's are a pass over every texel) are made once.
    std::lock_guard<std::mutex> lock(environmentMutex_);
    if (!(changedEnvironment_.description() == environment))
        changedEnvironment_ = environment_.changedTo(environment, scene_.textures);
    return changedEnvironment_;
}

SceneLayout SceneGeometry::layoutOf(const SceneState& state) const {
    if (triangleCount_ <= kFlatRebuildTriangles) return SceneLayout::Flat;
    return placementOf(state) == loaded_ ? SceneLayout::Flat : SceneLayout::Instanced;
}

RTCScene SceneGeometry::buildFlat(const Placement& placement, RTCBuildQuality quality) const {
    RTCScene scene = rtcNewScene(device_.get());
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene, quality);
    // Cut-out triangles after the meshes and quad lights, in the order of cutOutMeshes_.
    std::uint32_t cutOutId = std::uint32_t(scene_.meshes.size() + placement.quadLights.size());
    for (std::size_t i = 0; i < scene_.meshes.size(); ++i)
        if (meshes_[i])
            attachWorldMesh(scene, i, placement.meshes[i], std::uint32_t(i),
                            parts_[i].cutOut && !scene_.meshes[i].instanced ? cutOutId++ : 0);
    for (std::size_t j = 0; j < placement.quadLights.size(); ++j)
        attachWorldMesh(scene, unitQuad_, placement.quadLights[j],
                        std::uint32_t(scene_.meshes.size() + j));
    rtcCommitScene(scene);
    return scene;
}

RTCScene SceneGeometry::flatScene(const SceneState& state) const {
    Placement placement = placementOf(state);
    std::lock_guard lock(flatMutex_);
    const bool loaded = placement == loaded_;
    std::shared_ptr<FlatScene>& slot = loaded ? loadedFlat_ : latestFlat_;
    if (!slot || !(slot->placement == placement)) {
        auto flat = std::make_shared<FlatScene>();
        // The as-loaded BVH serves the whole session: the best one Embree builds. The others
        // serve until the next move.
        flat->scene =
            buildFlat(placement, loaded ? RTC_BUILD_QUALITY_HIGH : RTC_BUILD_QUALITY_MEDIUM);
        flat->placement = std::move(placement);
        slot = std::move(flat);
    }
    rtcRetainScene(slot->scene);
    return slot->scene;
}

}  // namespace igi
