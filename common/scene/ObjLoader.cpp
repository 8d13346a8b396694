#include "scene/ObjLoader.h"

#include <algorithm>
#include <cmath>
#include <istream>
#include <map>
#include <set>
#include <streambuf>
#include <unordered_map>

#include <spdlog/spdlog.h>
#include <tiny_obj_loader.h>
#include <glm/geometric.hpp>

#include "scene/MtlMaterials.h"
#include "scene/ObjText.h"
#include "scene/SceneError.h"

namespace igi {

namespace {

// Lets tinyobjloader read the bytes in place instead of copying 13 MB into a stringstream.
class MemoryStreamBuf : public std::streambuf {
  public:
    explicit MemoryStreamBuf(const std::string& text) {
        char* begin = const_cast<char*>(text.data());
        setg(begin, begin, begin + text.size());
    }
};

struct ParsedObj {
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
};

[[noreturn]] void failAtBadIndex(const std::string& objPath, const std::string& text,
                                 const std::string& fallback) {
    if (auto bad = findBadFaceIndex(text))
        throw SceneError::atLine(objPath, bad->line, bad->message);
    throw SceneError::inFile(objPath, fallback);
}

// tinyobjloader on `parsed`, which is `text` as the file has it (for error lines) or with a
// placeholder library in front.
ParsedObj runTinyObj(const std::string& objPath, const std::string& parsed, const std::string& text,
                     FileSourceMtlReader& reader) {
    ParsedObj obj;
    std::string warn, err;
    MemoryStreamBuf buffer(parsed);
    std::istream in(&buffer);
    const bool ok =
        tinyobj::LoadObj(&obj.attrib, &obj.shapes, &obj.materials, &warn, &err, &in, &reader,
                         /*triangulate=*/true, /*default_vcols_fallback=*/false);
    if (!ok) failAtBadIndex(objPath, text, err);
    // tinyobjloader only warns about these, and drops quads that have them.
    if (warn.find("out of bounds") != std::string::npos ||
        warn.find("invalid vertex index") != std::string::npos) {
        failAtBadIndex(objPath, text, warn);
    }
    if (!warn.empty()) spdlog::debug("{}: tinyobjloader: {}", objPath, warn);
    return obj;
}

// A `usemtl` of a name that no material library defines.
struct MissingMaterial {
    std::string name;
    int line = 0;
};

// Throws for a material library that cannot be read; returns the `usemtl` names that no
// library defines (each once, at its first line).
std::vector<MissingMaterial> checkMaterialStatements(
    const std::string& objPath, const std::string& text, const FileSourceMtlReader& reader,
    const std::vector<tinyobj::material_t>& materials) {
    std::vector<MissingMaterial> missingMaterials;
    for (const ObjMaterialStatement& st : scanMaterialStatements(text)) {
        for (const std::string& name : st.names) {
            if (st.isLibrary) {
                for (const std::string& missing : reader.missing()) {
                    if (missing != name) continue;
                    const std::string problem = reader.problem(name);
                    throw SceneError::atLine(objPath, st.line,
                                             "material library '" + name + "'" +
                                                 (problem.empty() ? " not found" : ": " + problem));
                }
                continue;
            }
            bool found = false;
            for (const auto& m : materials) found = found || m.name == name;
            for (const auto& m : missingMaterials) found = found || m.name == name;
            if (!found) missingMaterials.push_back({name, st.line});
        }
    }
    return missingMaterials;
}

// The name of the placeholder library: not a file name an OBJ can mean (tinyobjloader splits
// `mtllib` at white space, so it has none).
constexpr const char* kPlaceholderLibrary = "<igi:placeholder-materials>";

void checkFinite(const std::string& objPath, const std::string& text,
                 const std::vector<tinyobj::real_t>& values, int perElement, const char* keyword) {
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (std::isfinite(values[i])) continue;
        throw SceneError::atLine(objPath, lineOfStatement(text, keyword, i / perElement),
                                 std::string(keyword) + " coordinate is not finite");
    }
}

void checkIndices(const std::string& objPath, const std::string& text, const ParsedObj& obj) {
    const auto& a = obj.attrib;
    const long long nv = static_cast<long long>(a.vertices.size() / 3);
    const long long nn = static_cast<long long>(a.normals.size() / 3);
    const long long nt = static_cast<long long>(a.texcoords.size() / 2);
    for (const auto& shape : obj.shapes) {
        for (const tinyobj::index_t& i : shape.mesh.indices) {
            if (i.vertex_index < 0 || i.vertex_index >= nv || i.normal_index >= nn ||
                i.texcoord_index >= nt) {
                failAtBadIndex(objPath, text, "a face index is out of range");
            }
        }
    }
}

// Refuses a file that would make tinyobjloader allocate beyond the scene's limits, before it
// does, and charges its vertices and triangles to the scene.
void checkObjSize(const std::string& objPath, const std::string& text, SceneAssets& assets) {
    const ObjStatementCounts counts = countObjStatements(text);
    if (counts.indexBeyondInt) failAtBadIndex(objPath, text, "a face index is out of range");
    const SceneLimits& limits = assets.limits();
    if (counts.mostFaceCorners > limits.maxFaceCorners) {
        throw SceneError::atLine(objPath, counts.mostFaceCornersLine,
                                 "face has " + std::to_string(counts.mostFaceCorners) +
                                     " corners, over the limit of " +
                                     std::to_string(limits.maxFaceCorners));
    }
    if (counts.groups > limits.maxObjGroups) {
        throw SceneError::inFile(
            objPath, std::to_string(counts.groups) + " o and g statements, over the limit of " +
                         std::to_string(limits.maxObjGroups) + " per OBJ file");
    }
    // Each attribute has its own array: the longest is what the vertices cost.
    const std::uint64_t vertices = std::max({counts.positions, counts.normals, counts.texcoords});
    if (!assets.vertices().fits(vertices))
        throw SceneError::inFile(objPath, assets.vertices().exceeded(vertices));
    if (!assets.triangles().fits(counts.triangles))
        throw SceneError::inFile(objPath, assets.triangles().exceeded(counts.triangles));
    assets.vertices().add(vertices);
    assets.triangles().add(counts.triangles);
}

ParsedObj parseObj(const std::string& objPath, const std::string& text, FileSourceMtlReader& reader,
                   const FileSource& files) {
    if (auto line = findNonNumericVertexLine(text)) {
        throw SceneError::atLine(objPath, *line, "coordinate is not a finite number");
    }
    ParsedObj obj = runTinyObj(objPath, text, text, reader);
    const std::vector<MissingMaterial> missing =
        checkMaterialStatements(objPath, text, reader, obj.materials);
    if (!missing.empty()) {
        // As Blender and tinyobjloader do, a missing material is the default one, under its
        // own name so that a scene file's "materials" section can still set it. tinyobjloader
        // keeps no name for a face whose material is unknown, so the file is read once more
        // with a library of placeholders in front of its own.
        std::string libraries;
        for (const auto& l : reader.libraries())
            libraries += (libraries.empty() ? "" : ", ") + files.displayName(l);
        if (libraries.empty()) libraries = "any material library (no mtllib loaded)";
        std::vector<std::string> names;
        for (const MissingMaterial& m : missing) {
            spdlog::warn(
                "{}:{}: usemtl '{}': no material of that name in {}; using the default "
                "material (grey, Kd 0.8) under that name, which a scene file's "
                "\"materials\" section can set",
                files.displayName(objPath), m.line, m.name, libraries);
            names.push_back(m.name);
        }
        reader.addPlaceholders(kPlaceholderLibrary, names);
        reader.restart();
        obj = runTinyObj(objPath, std::string("mtllib ") + kPlaceholderLibrary + "\n" + text, text,
                         reader);
    }
    checkFinite(objPath, text, obj.attrib.vertices, 3, "v");
    checkFinite(objPath, text, obj.attrib.normals, 3, "vn");
    checkFinite(objPath, text, obj.attrib.texcoords, 2, "vt");
    checkIndices(objPath, text, obj);
    return obj;
}

// Appends the file's materials to the scene; returns the scene index of its first one.
std::uint32_t appendMaterials(const ParsedObj& obj, const FileSourceMtlReader& reader,
                              SceneAssets& assets) {
    auto& materials = assets.scene().materials;
    const auto base = static_cast<std::uint32_t>(materials.size());
    std::map<std::string, std::set<std::string>> unmodelled;  // by MTL file
    for (std::size_t i = 0; i < obj.materials.size(); ++i) {
        const std::string& mtlPath = reader.materialFiles().at(i);
        materials.push_back(
            materialFromMtl(obj.materials[i], mtlPath, reader.text(mtlPath), assets));
        for (const std::string& s : unmodelledMtlStatements(obj.materials[i]))
            unmodelled[mtlPath].insert(s);
    }
    for (const auto& [mtlPath, statements] : unmodelled) {
        std::string list;
        for (const std::string& s : statements) list += (list.empty() ? "" : ", ") + s;
        spdlog::warn("{}: statements not modelled, rendered without them: {}", mtlPath, list);
    }
    return base;
}

struct VertexKey {
    int v, vn, vt;
    bool operator==(const VertexKey&) const = default;
};

struct VertexKeyHash {
    std::size_t operator()(const VertexKey& k) const {
        std::uint64_t h = static_cast<std::uint32_t>(k.v);
        h = h * 0x9E3779B97F4A7C15ull ^ static_cast<std::uint32_t>(k.vn);
        h = h * 0x9E3779B97F4A7C15ull ^ static_cast<std::uint32_t>(k.vt);
        return static_cast<std::size_t>(h ^ (h >> 29));
    }
};

// Turns OBJ's three index streams into one: a vertex per distinct (v, vn, vt) triple.
class DeIndexer {
  public:
    DeIndexer(const tinyobj::attrib_t& attrib, Mesh& mesh) : a_(attrib), mesh_(mesh) {}

    void useAttributes(bool normals, bool uvs) {
        normals_ = normals;
        uvs_ = uvs;
    }

    void addTriangle(const tinyobj::index_t* corners, std::uint32_t material) {
        const glm::vec3 p0 = position(corners[0]), p1 = position(corners[1]),
                        p2 = position(corners[2]);
        const glm::vec3 cross = glm::cross(p1 - p0, p2 - p0);
        if (!(glm::length(cross) > 0.0f)) ++degenerate_;
        const glm::vec3 faceNormal = degenerateSafeNormal(cross);
        glm::uvec3 tri;
        for (int c = 0; c < 3; ++c) tri[c] = vertex(corners[c], faceNormal);
        mesh_.triangles.push_back(tri);
        mesh_.materialIds.push_back(material);
    }

    std::size_t degenerateCount() const { return degenerate_; }

  private:
    glm::vec3 position(const tinyobj::index_t& i) const {
        const auto* p = &a_.vertices[3 * static_cast<std::size_t>(i.vertex_index)];
        return {p[0], p[1], p[2]};
    }

    static glm::vec3 degenerateSafeNormal(glm::vec3 cross) {
        const float len = glm::length(cross);
        return len > 0.0f && std::isfinite(len) ? cross / len : glm::vec3(0.0f, 0.0f, 1.0f);
    }

    // The file's normal, normalized, or nothing when the corner has none or a zero one.
    std::optional<glm::vec3> fileNormal(const tinyobj::index_t& i) const {
        if (i.normal_index < 0) return std::nullopt;
        const auto* n = &a_.normals[3 * static_cast<std::size_t>(i.normal_index)];
        const glm::vec3 v(n[0], n[1], n[2]);
        const float len = glm::length(v);
        if (!(len > 0.0f) || !std::isfinite(len)) return std::nullopt;
        return v / len;
    }

    std::uint32_t vertex(const tinyobj::index_t& i, glm::vec3 faceNormal) {
        const std::optional<glm::vec3> n = normals_ ? fileNormal(i) : std::nullopt;
        // Corners without a usable normal in a mesh that has normals are flat-shaded: a key
        // of their own per triangle, so that the face normal is not shared across an edge.
        const int vnKey = !normals_ ? -1
                          : n       ? i.normal_index
                                    : -2 - static_cast<int>(mesh_.triangles.size());
        const VertexKey key{i.vertex_index, vnKey, uvs_ ? i.texcoord_index : -1};
        auto [it, inserted] =
            map_.try_emplace(key, static_cast<std::uint32_t>(mesh_.positions.size()));
        if (!inserted) return it->second;
        mesh_.positions.push_back(position(i));
        if (normals_) mesh_.normals.push_back(n ? *n : faceNormal);
        if (uvs_) mesh_.uvs.push_back(uv(i));
        return it->second;
    }

    glm::vec2 uv(const tinyobj::index_t& i) const {
        if (i.texcoord_index < 0) return glm::vec2(0.0f);
        const auto* t = &a_.texcoords[2 * static_cast<std::size_t>(i.texcoord_index)];
        return {t[0], t[1]};
    }

    const tinyobj::attrib_t& a_;
    Mesh& mesh_;
    bool normals_ = false;
    bool uvs_ = false;
    std::size_t degenerate_ = 0;
    std::unordered_map<VertexKey, std::uint32_t, VertexKeyHash> map_;
};

void buildMesh(const std::string& objPath, const ParsedObj& obj, std::uint32_t materialBase,
               SceneAssets& assets, Mesh& mesh) {
    bool anyNormal = false, anyUv = false;
    std::size_t cornerCount = 0;
    for (const auto& shape : obj.shapes) {
        cornerCount += shape.mesh.indices.size();
        for (const auto& i : shape.mesh.indices) {
            anyNormal = anyNormal || i.normal_index >= 0;
            anyUv = anyUv || i.texcoord_index >= 0;
        }
    }
    DeIndexer deIndexer(obj.attrib, mesh);
    deIndexer.useAttributes(anyNormal, anyUv);
    mesh.triangles.reserve(cornerCount / 3);
    mesh.materialIds.reserve(cornerCount / 3);

    const auto fileMaterials = static_cast<int>(obj.materials.size());
    std::optional<std::uint32_t> defaultId;
    for (const auto& shape : obj.shapes) {
        std::size_t offset = 0;
        for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
            const std::size_t n = shape.mesh.num_face_vertices[f];
            const int id = f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1;
            if (n == 3) {
                std::uint32_t material;
                if (id >= 0 && id < fileMaterials) {
                    material = materialBase + static_cast<std::uint32_t>(id);
                } else {
                    if (!defaultId) {
                        defaultId = static_cast<std::uint32_t>(assets.scene().materials.size());
                        assets.scene().materials.push_back(defaultMaterial());
                    }
                    material = *defaultId;
                }
                deIndexer.addTriangle(&shape.mesh.indices[offset], material);
            }
            offset += n;
        }
    }
    if (deIndexer.degenerateCount() > 0) {
        spdlog::debug("{}: {} degenerate (zero-area) triangles kept", objPath,
                      deIndexer.degenerateCount());
    }
}

}  // namespace

void loadObj(const std::string& objPath, SceneAssets& assets, Mesh& mesh) {
    const std::string text = assets.files().read(objPath);
    checkObjSize(objPath, text, assets);
    FileSourceMtlReader reader(assets.files(), objPath, assets.limits().maxMaterials,
                               assets.scene().materials.size());
    const ParsedObj obj = parseObj(objPath, text, reader, assets.files());
    const std::uint32_t base = appendMaterials(obj, reader, assets);
    buildMesh(objPath, obj, base, assets, mesh);
    spdlog::debug("{}: {} triangles, {} vertices, {} materials", objPath, mesh.triangles.size(),
                  mesh.positions.size(), obj.materials.size());
}

}  // namespace igi
