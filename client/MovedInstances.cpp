#include "MovedInstances.h"

#include <algorithm>

#include <glm/gtc/type_ptr.hpp>

#include "TraceableScene.h"

namespace igi {
namespace {

void addInstance(RTCDevice device, RTCScene top, RTCScene object, const glm::mat4& objectToWorld) {
    RTCGeometry instance = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(instance, object);
    rtcSetGeometryTransform(instance, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR,
                            glm::value_ptr(objectToWorld));
    rtcCommitGeometry(instance);
    rtcAttachGeometry(top, instance);
    rtcReleaseGeometry(instance);
}

bool sameGeometry(const QuadLight& a, const QuadLight& b) {
    return a.corner == b.corner && a.edge1 == b.edge1 && a.edge2 == b.edge2;
}

}  // namespace

MovedInstances::MovedInstances(const SceneGeometry& geometry, const SceneState& before,
                               const SceneState& after) {
    for (std::uint32_t i = 0; i < after.transforms.size() && i < before.transforms.size(); ++i)
        if (!(before.transforms[i] == after.transforms[i]) && geometry.mesh(i))
            meshes_.push_back(i);
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
    RTCScene top = rtcNewScene(geometry.device().get());
    rtcSetSceneFlags(top, RTC_SCENE_FLAG_ROBUST);
    for (std::uint32_t i : meshes_)
        addInstance(geometry.device().get(), top, geometry.mesh(i), state.transforms[i].matrix());
    for (std::uint32_t i : lights_)
        addInstance(geometry.device().get(), top, geometry.unitQuadScene(),
                    TraceableScene::quadLightMatrix(state.quadLights[i]));
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
