#pragma once

#include <cstdint>
#include <optional>

#include <glm/vec3.hpp>

#include "scene/Scene.h"
#include "scene/SceneState.h"

namespace igi {

/// What the camera sees at one image position.
struct PickHit {
    std::uint32_t mesh = 0;  ///< index into Scene::meshes
    glm::vec3 point{0.0f};   ///< world space
    float distance = 0;      ///< along the camera ray, world units
};

/// The first surface the camera ray through image position (x, y) (pixels from the top-left
/// corner of the image) meets, with the meshes placed as `state` says; none if it leaves the
/// scene. Used by the `pick` control command (the web view's click-to-select).
///
/// It runs on the master, which has no Embree: every triangle is tested, a few ns each, which is
/// milliseconds for a 100K-triangle scene. That is right for a click and wrong for a frame.
std::optional<PickHit> pickObject(const Scene& scene, const SceneState& state, float x, float y);

}  // namespace igi
