#include "tracing/MovedInstances.h"

#include <algorithm>

#include "tracing/TraceableScene.h"

namespace igi {
namespace {

bool sameGeometry(const QuadLight& a, const QuadLight& b) {
    return a.corner == b.corner && a.edge1 == b.edge1 && a.edge2 == b.edge2;
}

}  // namespace

MovedInstances::MovedInstances(const SceneGeometry& geometry, const SceneState& before,
                               const SceneState& after) {
    // An instance of a glTF file's shared primitive moves with its object.
    const Scene& scene = geometry.scene();
    for (std::uint32_t i = 0; i < after.transforms.size() && i < before.transforms.size(); ++i) {
        const std::uint32_t object = objectOf(scene, i);
        if (!(before.transforms[object] == after.transforms[object]) && geometry.mesh(i))
            meshes_.push_back(i);
    }
    for (std::uint32_t i = 0; i < after.quadLights.size() && i < before.quadLights.size(); ++i)
        if (!sameGeometry(before.quadLights[i], after.quadLights[i])) lights_.push_back(i);
    lightsMoved_ = lights_.size();
    if (!any()) return;
    before_ = build(geometry, before);
    after_ = build(geometry, after);
}

MovedInstances::~MovedInstances() {
    if (before_) rtcReleaseScene(before_);
    if (after_) rtcReleaseScene(after_);
}

RTCScene MovedInstances::build(const SceneGeometry& geometry, const SceneState& state) const {
    // Laid out as the version of `state` is (in world space or as instances), so that a ray
    // meets a moved object here exactly where it meets it in that version.
    const bool flat = geometry.layoutOf(state) == SceneLayout::Flat;
    RTCScene top = rtcNewScene(geometry.device().get());
    rtcSetSceneFlags(top, RTC_SCENE_FLAG_ROBUST);
    std::uint32_t id = 0;
    for (std::uint32_t i : meshes_) {
        const glm::mat4 m = meshToWorld(geometry.scene(), state.transforms, i);
        if (flat) {
            const std::uint32_t opaqueId = id++;
            geometry.attachWorldMesh(top, i, m, opaqueId, geometry.hasCutOuts(i) ? id++ : 0);
        } else
            geometry.attachInstance(top, geometry.mesh(i), m, id++);
    }
    for (std::uint32_t i : lights_) {
        const glm::mat4 m = TraceableScene::quadLightMatrix(state.quadLights[i]);
        if (flat)
            geometry.attachWorldMesh(top, geometry.unitQuad(), m, id++);
        else
            geometry.attachInstance(top, geometry.unitQuadScene(), m, id++);
    }
    rtcCommitScene(top);
    return top;
}

bool MovedInstances::meshMoved(std::uint32_t mesh) const {
    return std::binary_search(meshes_.begin(), meshes_.end(), mesh);
}

bool MovedInstances::occluded(bool before, glm::vec3 origin, glm::vec3 direction, float tfar,
                              RayCounters& counters) const {
    RTCScene scene = before ? before_ : after_;
    return scene && TraceableScene::occludedIn(scene, origin, direction, tfar, counters);
}

}  // namespace igi
