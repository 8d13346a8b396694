#include "SceneGeometry.h"

#include <stdexcept>

namespace igi {

SceneGeometry::SceneGeometry(const EmbreeDevice& device, const Scene& scene)
    : device_(device), scene_(scene) {
    for (const Mesh& mesh : scene.meshes)
        meshes_.push_back(mesh.triangles.empty() ? nullptr : build(mesh));
    unitQuad_.name = "unit quad";
    unitQuad_.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    unitQuad_.triangles = {{0, 1, 2}, {0, 2, 3}};
    unitQuad_.materialIds = {0, 0};  // each quad light instance says which material it uses
    unitQuadScene_ = build(unitQuad_);
}

SceneGeometry::~SceneGeometry() {
    for (RTCScene s : meshes_)
        if (s) rtcReleaseScene(s);
    if (unitQuadScene_) rtcReleaseScene(unitQuadScene_);
}

RTCScene SceneGeometry::build(const Mesh& mesh) const {
    RTCScene scene = rtcNewScene(device_.get());
    // Robust traversal: no hit is lost on shared edges, so closed meshes do not leak light.
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry geom = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), mesh.positions.size()));
    auto* indices = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(unsigned), mesh.triangles.size()));
    if (!vertices || !indices)
        throw std::runtime_error("Embree could not allocate the buffers of mesh " + mesh.name);
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
        for (int c = 0; c < 3; ++c) vertices[3 * i + c] = mesh.positions[i][c];
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
        for (int c = 0; c < 3; ++c) indices[3 * i + c] = mesh.triangles[i][c];
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene);
    return scene;
}

}  // namespace igi
