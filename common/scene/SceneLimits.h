#pragma once

// What a scene may ask of the loader. Scene files come from users, like network messages: a
// file that claims a 100000 x 100000 texture or a billion triangles is refused with a clear
// error before anything of that size is allocated, and paths may not leave the scene's folder
// unless the caller allows it. docs/SCENE_FORMAT.md, "Limits and safety", explains each value.

#include <cstddef>
#include <cstdint>
#include <string>

namespace igi {

constexpr std::uint64_t kMiB = 1024ull * 1024;
constexpr std::uint64_t kGiB = 1024ull * kMiB;

struct SceneLimits {
    /// The JSON scene file itself (a scene file is a few kB; 100,000 lights are ~15 MB).
    std::uint64_t maxSceneFileBytes = 64 * kMiB;
    /// Any one file a scene references (OBJ, MTL, glTF, .bin, image).
    std::uint64_t maxFileBytes = 2 * kGiB;
    /// All files of one scene together (they are kept in memory to ship to the clients), and
    /// the bytes one glTF file's buffers and images expand to.
    std::uint64_t maxTotalBytes = 4 * kGiB;
    std::size_t maxMeshes = 100'000;
    /// Point and quad lights, glTF lights included.
    std::size_t maxLights = 100'000;
    /// Materials read from MTL and glTF files.
    std::size_t maxMaterials = 100'000;
    /// Triangles of the whole scene (a glTF mesh instanced by several nodes counts each time).
    std::uint64_t maxTriangles = 50'000'000;
    /// Vertices of the whole scene: OBJ v (or vn, vt, whichever is most) statements, glTF
    /// POSITION counts; also the largest glTF accessor.
    std::uint64_t maxVertices = 150'000'000;
    /// Corners of one OBJ face: tinyobjloader's ear clipping is quadratic in them.
    std::size_t maxFaceCorners = 256;
    /// `o` and `g` statements of one OBJ file (each is a shape object in tinyobjloader).
    std::size_t maxObjGroups = 1'000'000;
    /// Top-level glTF objects (nodes, meshes, primitives, accessors, ...) of one glTF file,
    /// and its JSON values: tinygltf's objects are 300 bytes to 2 kB each.
    std::size_t maxGltfObjects = 1'000'000;
    std::size_t maxGltfJsonValues = 10'000'000;
    /// One texture: 8192 x 8192 is 768 MiB of linear RGB floats.
    std::uint64_t maxTexturePixels = 8192ull * 8192;
    /// All textures of the scene together (3 GiB of texels).
    std::uint64_t maxTotalTexturePixels = 4 * 8192ull * 8192;
};

/// How loadSceneFile may read the disk.
struct SceneLoadOptions {
    /// Paths that are absolute, climb out of the scene file's folder with "..", or lead out of
    /// it through a symbolic link are refused unless this is set (igi-master's
    /// --allow-outside-paths). Only for scene files you trust.
    bool allowOutsidePaths = false;
    /// Light the scene with a headlight at the camera even when it has lights of its own
    /// (igi-master --headlight); the bundle's scene text says so, for the clients.
    bool headlight = false;
    SceneLimits limits;
};

/// A running total against a limit (triangles, bytes, texture pixels, ...).
class Budget {
  public:
    /// `unit` and `scope` name it in messages: "triangles", "per scene".
    Budget(std::uint64_t limit, std::string unit, std::string scope);

    bool fits(std::uint64_t amount) const;
    /// Adds `amount`; the caller has checked fits().
    void add(std::uint64_t amount);
    /// Why `amount` does not fit: "12 more triangles would exceed the limit of 50000000 per
    /// scene (49999990 already)".
    std::string exceeded(std::uint64_t amount) const;
    std::uint64_t used() const { return used_; }
    std::uint64_t remaining() const { return limit_ - used_; }

  private:
    std::uint64_t limit_;
    std::uint64_t used_ = 0;
    std::string unit_;
    std::string scope_;
};

}  // namespace igi
