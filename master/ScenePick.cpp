#include "ScenePick.h"

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include "scene/CameraModel.h"

namespace igi {
namespace {

// Möller-Trumbore, both sides: the nearest t in (0, best) or best itself. Directions need not be
// unit length: t is in the units of the ray that was given.
float intersect(glm::vec3 o, glm::vec3 d, glm::vec3 a, glm::vec3 b, glm::vec3 c, float best) {
    const glm::vec3 e1 = b - a, e2 = c - a;
    const glm::vec3 p = glm::cross(d, e2);
    const float det = glm::dot(e1, p);
    if (!(std::abs(det) > 0.0f)) return best;
    const float inv = 1.0f / det;
    const glm::vec3 s = o - a;
    const float u = glm::dot(s, p) * inv;
    if (u < 0.0f || u > 1.0f) return best;
    const glm::vec3 q = glm::cross(s, e1);
    const float v = glm::dot(d, q) * inv;
    if (v < 0.0f || u + v > 1.0f) return best;
    const float t = glm::dot(e2, q) * inv;
    return t > 0.0f && t < best ? t : best;
}

}  // namespace

std::optional<PickHit> pickObject(const Scene& scene, const SceneState& state, float x, float y) {
    const CameraModel camera(state.camera, scene.image.width, scene.image.height);
    const glm::vec3 origin = camera.origin();
    const glm::vec3 direction = camera.direction(x, y);
    std::optional<PickHit> hit;
    float best = std::numeric_limits<float>::infinity();
    for (std::uint32_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = geometryOf(scene, m);
        // The ray goes into the mesh's own space (one inverse per mesh) rather than every vertex
        // into the world's; an affine map keeps the ray parameter t, so distances compare.
        const glm::mat4 toObject = glm::inverse(meshToWorld(scene, state.transforms, m));
        const glm::vec3 o = glm::vec3(toObject * glm::vec4(origin, 1.0f));
        const glm::vec3 d = glm::mat3(toObject) * direction;
        const float before = best;
        for (const glm::uvec3& t : mesh.triangles)
            best = intersect(o, d, mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z],
                             best);
        // An instance's hit picks the object it is a part of.
        if (best < before) hit = PickHit{objectOf(scene, m), origin + best * direction, best};
    }
    return hit;
}

}  // namespace igi
