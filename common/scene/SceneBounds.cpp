#include "scene/SceneBounds.h"

namespace igi {

Bounds3 worldBounds(const Scene& scene) {
    Bounds3 b;
    std::vector<Transform> transforms;
    for (const Mesh& mesh : scene.meshes) transforms.push_back(mesh.transform);
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
        const glm::mat4 m = meshToWorld(scene, transforms, i);
        for (const glm::vec3& p : geometryOf(scene, i).positions)
            b.extend(glm::vec3(m * glm::vec4(p, 1.0f)));
    }
    for (const QuadLight& q : scene.quadLights) {
        b.extend(q.corner);
        b.extend(q.corner + q.edge1);
        b.extend(q.corner + q.edge2);
        b.extend(q.corner + q.edge1 + q.edge2);
    }
    // A directional light has no position: it is everywhere outside.
    for (const PunctualLight& l : scene.punctualLights)
        if (l.kind != LightKind::Directional) b.extend(l.position);
    return b;
}

}  // namespace igi
