#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
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

    // Instancing (docs/SCENE_FORMAT.md, "Instances"): geometry placed several times (a glTF
    // primitive under several nodes, an OBJ file named by several entries of the scene file)
    // is held and built into a BVH once, and each placement is a mesh of its own that the
    // client traces as an Embree instance of it. Meshes placed once keep these defaults.
    /// Index in Scene::meshes of the mesh holding this one's vertices, triangles and
    /// materialIds (its own are empty), or -1: its own.
    std::int32_t geometryOf = -1;
    /// Index in Scene::meshes of the object (an entry of the scene file) this mesh is a part
    /// of: its transform places the part, its name is the one commands use; -1: an object.
    std::int32_t partOf = -1;
    /// The material of every triangle (a glTF primitive's, which differs between placements
    /// of the same geometry), or -1: the geometry's materialIds.
    std::int32_t material = -1;
    /// The placement in the object's space, before the object's transform (a glTF node's
    /// matrix); identity for an OBJ file loaded again.
    glm::mat4 local{1.0f};
    /// Traced as an instance of its geometry's own BVH: the geometry has several placements.
    bool instanced = false;
};

}  // namespace igi
