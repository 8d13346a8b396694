#pragma once

// A first, cheap pass over a glTF file's JSON (nlohmann's SAX parser: nothing is built) that
// measures what tinygltf would allocate: its objects, the bytes its buffers and images
// expand to, and the files they name. The glTF loader refuses a hostile file from these
// numbers before tinygltf parses it (tinygltf's objects are 300 bytes to 2 kB each, and it
// copies a GLB's binary chunk into every buffer that names it).

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace igi {

struct GltfPrescan {
    struct Buffer {
        std::string uri;  ///< as written (may be a data: URI, or empty in a GLB)
        std::uint64_t byteLength = 0;
    };
    struct Image {
        std::string uri;
        long long bufferView = -1;
    };
    struct BufferView {
        long long buffer = -1;
        std::uint64_t byteOffset = 0;
        std::uint64_t byteLength = 0;
    };
    std::uint64_t jsonValues = 0;
    /// Deepest nesting of arrays and objects (tinygltf copies "extras" recursively).
    std::size_t depth = 0;
    /// Elements of each top-level array ("nodes": 12, "materials": 3, ...).
    std::map<std::string, std::uint64_t> arrayElements;
    /// Elements of every meshes[i].primitives.
    std::uint64_t primitives = 0;
    std::vector<Buffer> buffers;
    std::vector<Image> images;
    std::vector<BufferView> bufferViews;

    /// Top-level objects and primitives together.
    std::uint64_t objects() const;
    std::uint64_t count(const std::string& array) const;
};

/// Measures `json`, stopping early once it has seen more than `maxJsonValues` values or a
/// nesting deeper than `maxDepth` (then jsonValues or depth is over). Throws SceneError
/// naming `file` on a JSON syntax error.
GltfPrescan prescanGltfJson(const std::string& json, const std::string& file,
                            std::uint64_t maxJsonValues, std::size_t maxDepth);

/// The JSON chunk of a binary glTF (.glb) file; throws SceneError naming `file` when the
/// header is not one tinygltf would accept.
std::string glbJsonChunk(const std::string& bytes, const std::string& file);

/// A URI's file name as tinygltf decodes it ("%20" and "+" are spaces).
std::string decodeUri(const std::string& uri);

}  // namespace igi
