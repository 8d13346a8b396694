#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "scene/Transform.h"

namespace igi {

/// One object of the scene: a triangle mesh in object space and where it is placed.
/// Vertex attributes are per vertex (already de-indexed from OBJ's separate index streams).
struct Mesh {
    std::string name;  ///< the scene file's `name`, else the file's stem
    std::string file;  ///< the file it came from, relative to the scene file, for messages
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;  ///< empty, or one per position
    std::vector<glm::vec2> uvs;      ///< empty, or one per position
    /// Empty, or one per position (glTF TANGENT): xyz the unit tangent toward +u, w the sign of
    /// the bitangent, cross(normal, tangent) * w, which points toward +v (igi's v, up in the
    /// image). Without them, normal maps take the tangent frame from each triangle's uvs.
    std::vector<glm::vec4> tangents;
    /// Empty, or one per position (glTF COLOR_0, linear RGB): multiplies the base colour.
    std::vector<glm::vec3> colors;
    std::vector<glm::uvec3> triangles;
    std::vector<std::uint32_t> materialIds;  ///< one per triangle, index into Scene::materials
    Transform transform;
};

}  // namespace igi
