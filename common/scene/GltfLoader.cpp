#include "scene/GltfLoader.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <set>

#include <spdlog/spdlog.h>
#include <tiny_gltf.h>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>

#include "scene/GltfPrescan.h"
#include "scene/MtlMaterials.h"
#include "scene/SceneError.h"
#include "scene/TextureLoader.h"

namespace igi {

namespace {

// Luminous efficacy of the specification's photometric light units (lm/W).
constexpr double kLumensPerWatt = 683.0;
constexpr int kMaxNodeDepth = 256;
// glTF itself nests about 8 levels; tinygltf copies "extras" recursively, so a deeper nest
// could exhaust the stack.
constexpr std::size_t kMaxGltfJsonDepth = 128;

// ---- Reading through the FileSource -------------------------------------------------------

struct FsContext {
    FileSource* files;
    std::string gltfPath;
    Budget* expanded;     // bytes of buffers and images loaded so far
    std::string refusal;  // why a file was refused, reported instead of tinygltf's message
    std::string resolve(const std::string& uri) const { return resolveRelative(gltfPath, uri); }
};

bool fileExists(const std::string& uri, void* user) {
    const auto* ctx = static_cast<FsContext*>(user);
    try {
        return ctx->files->exists(ctx->resolve(uri));
    } catch (const std::exception&) {
        return false;
    }
}

std::string expandPath(const std::string& uri, void*) {
    return uri;
}

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& uri,
                   void* user) {
    auto* ctx = static_cast<FsContext*>(user);
    try {
        const std::string bytes = ctx->files->read(ctx->resolve(uri));
        // Several buffers or images may name one file: each gets its own copy.
        if (!ctx->expanded->fits(bytes.size())) {
            throw SceneError::inFile(ctx->resolve(uri), ctx->expanded->exceeded(bytes.size()));
        }
        ctx->expanded->add(bytes.size());
        out->assign(bytes.begin(), bytes.end());
        return true;
    } catch (const std::exception& e) {
        // Never let an exception cross tinygltf's frames.
        if (ctx->refusal.empty()) ctx->refusal = e.what();
        if (err) *err += e.what();
        return false;
    }
}

bool writeWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&,
                    void*) {
    if (err) *err += "writing is not supported";
    return false;
}

// Images are decoded later with OpenImageIO, and only those used as colour textures: keep the
// encoded bytes.
bool keepEncodedImage(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
    image->image.assign(bytes, bytes + size);
    image->as_is = true;
    return true;
}

void checkUri(const std::string& path, const std::string& uri, const std::string& where,
              FileSource& files) {
    try {
        files.checkPath(resolveRelative(path, decodeUri(uri)));
    } catch (const SceneError& e) {
        throw SceneError::atPath(path, where, e.message());
    }
}

void charge(Budget& budget, std::uint64_t bytes, const std::string& path,
            const std::string& where) {
    if (!budget.fits(bytes)) throw SceneError::atPath(path, where, budget.exceeded(bytes));
    budget.add(bytes);
}

// A buffer's data is exactly its byteLength once tinygltf has loaded it (it checks), so the
// JSON alone tells whether a view lies inside.
void checkImageView(const GltfPrescan& scan, long long viewIndex, const std::string& path,
                    const std::string& where) {
    if (viewIndex >= static_cast<long long>(scan.bufferViews.size()))
        throw SceneError::atPath(path, where, "buffer view does not exist");
    const GltfPrescan::BufferView& view = scan.bufferViews[viewIndex];
    if (view.buffer < 0 || view.buffer >= static_cast<long long>(scan.buffers.size()))
        throw SceneError::atPath(path, where, "its buffer view's buffer does not exist");
    const std::uint64_t size = scan.buffers[view.buffer].byteLength;
    if (view.byteOffset >= size || view.byteLength > size - view.byteOffset ||
        view.byteLength > static_cast<std::uint64_t>(std::numeric_limits<int>::max())) {
        throw SceneError::atPath(path, where, "its buffer view reaches past the end of its buffer");
    }
}

// Refuses, from the JSON alone, a file whose parse would allocate beyond the limits or that
// names files outside the scene's folder; charges `expanded` with the bytes tinygltf will
// copy out of the file itself (a GLB's binary chunk, buffer views holding images).
void checkBeforeParsing(const std::string& path, const std::string& json, SceneAssets& assets,
                        Budget& expanded) {
    const SceneLimits& limits = assets.limits();
    const GltfPrescan scan =
        prescanGltfJson(json, path, limits.maxGltfJsonValues, kMaxGltfJsonDepth);
    if (scan.jsonValues > limits.maxGltfJsonValues) {
        throw SceneError::inFile(path, "more than " + std::to_string(limits.maxGltfJsonValues) +
                                           " JSON values, over the limit per glTF file");
    }
    if (scan.depth > kMaxGltfJsonDepth) {
        throw SceneError::inFile(
            path, "JSON nested deeper than " + std::to_string(kMaxGltfJsonDepth) + " levels");
    }
    if (scan.objects() > limits.maxGltfObjects) {
        throw SceneError::inFile(path, std::to_string(scan.objects()) +
                                           " objects (nodes, meshes, primitives, accessors, ...), "
                                           "over the limit of " +
                                           std::to_string(limits.maxGltfObjects) +
                                           " per glTF file");
    }
    assets.checkMaterialCount(scan.count("materials"), path);
    for (std::size_t i = 0; i < scan.buffers.size(); ++i) {
        const auto& b = scan.buffers[i];
        const std::string where = "/buffers/" + std::to_string(i);
        if (b.uri.empty()) {
            charge(expanded, b.byteLength, path, where);  // a copy of the GLB's binary chunk
        } else if (!tinygltf::IsDataURI(b.uri)) {
            checkUri(path, b.uri, where + "/uri", assets.files());
        }
    }
    for (std::size_t i = 0; i < scan.images.size(); ++i) {
        const auto& image = scan.images[i];
        const std::string where = "/images/" + std::to_string(i);
        if (!image.uri.empty() && !tinygltf::IsDataURI(image.uri)) {
            checkUri(path, image.uri, where + "/uri", assets.files());
        } else if (image.bufferView >= 0) {
            // tinygltf 2.7 copies an image's buffer view without checking that it lies inside
            // its buffer (a read past the end): check it here.
            checkImageView(scan, image.bufferView, path, where);
            charge(expanded, scan.bufferViews[image.bufferView].byteLength, path, where);
        }
    }
}

// tinygltf's message for a missing buffer is "File not found : X.bin" and a newline: say it
// in the form of every other scene error, as a missing image is said.
[[noreturn]] void failToLoad(const std::string& path, std::string err) {
    static const std::string notFound = "File not found : ";
    if (err.rfind(notFound, 0) == 0) {
        const std::size_t end = err.find('\n');
        const std::string uri = err.substr(
            notFound.size(), end == std::string::npos ? std::string::npos : end - notFound.size());
        throw SceneError::inFile(path, "buffer '" + uri + "' not found or unreadable");
    }
    while (!err.empty() && std::isspace(static_cast<unsigned char>(err.back()))) err.pop_back();
    std::replace(err.begin(), err.end(), '\n', ' ');
    throw SceneError::inFile(path, "cannot load glTF: " + err);
}

tinygltf::Model parseGltf(const std::string& path, SceneAssets& assets) {
    FileSource& files = assets.files();
    const std::string bytes = files.read(path);
    // tinygltf takes 32-bit sizes.
    if (bytes.size() > std::numeric_limits<unsigned>::max())
        throw SceneError::inFile(path, "a glTF file must be smaller than 4 GiB");
    const bool binary = bytes.rfind("glTF", 0) == 0;
    Budget expanded(assets.limits().maxTotalBytes, "bytes of buffers and images", "per glTF file");
    checkBeforeParsing(path, binary ? glbJsonChunk(bytes, path) : bytes, assets, expanded);

    FsContext ctx{&files, path, &expanded, {}};
    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks({&fileExists, &expandPath, &readWholeFile, &writeWholeFile, &ctx});
    loader.SetImageLoader(&keepEncodedImage, nullptr);
    tinygltf::Model model;
    std::string err, warn;
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
    const bool ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, data,
                                                         static_cast<unsigned>(bytes.size()), "")
                           : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(),
                                                        static_cast<unsigned>(bytes.size()), "");
    // Also when tinygltf carried on (it only warns about images it cannot load).
    if (!ctx.refusal.empty()) throw SceneError::inFile(path, "cannot load glTF: " + ctx.refusal);
    if (!ok) failToLoad(path, err);
    if (!warn.empty()) spdlog::debug("{}: tinygltf: {}", path, warn);
    return model;
}

// ---- Small helpers ------------------------------------------------------------------------

double extensionNumber(const tinygltf::ExtensionMap& extensions, const char* extension,
                       const char* key, double fallback) {
    auto it = extensions.find(extension);
    if (it == extensions.end() || !it->second.Has(key)) return fallback;
    const tinygltf::Value& v = it->second.Get(key);
    return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
}

// The texCoord a textureInfo's lookup uses: KHR_texture_transform's, when it says one.
template <typename Info>
int texCoordOf(const Info& info) {
    auto it = info.extensions.find("KHR_texture_transform");
    if (it != info.extensions.end() && it->second.Has("texCoord")) {
        const tinygltf::Value& v = it->second.Get("texCoord");
        if (v.IsNumber()) return static_cast<int>(v.GetNumberAsDouble());
    }
    return info.texCoord;
}

// A textureInfo's KHR_texture_transform (offset, rotation, scale; its texCoord is texCoordOf's)
// in igi's uvs. glTF's: g' = offset + R(rotation) S(scale) g, R's rows (cos, sin), (-sin, cos),
// with g = (u, 1 - v) of igi's (u, v) (glTF's v runs down the image). Inactive without the
// extension, or when it is the identity.
UvTransform uvTransformOf(const tinygltf::ExtensionMap& extensions) {
    UvTransform t;
    auto it = extensions.find("KHR_texture_transform");
    if (it == extensions.end() || !it->second.IsObject()) return t;
    const tinygltf::Value& ext = it->second;
    auto number = [](const tinygltf::Value& v, double fallback) {
        const double x = v.IsNumber() ? v.GetNumberAsDouble() : fallback;
        return std::isfinite(x) ? x : fallback;
    };
    auto pair = [&](const char* key, glm::dvec2 fallback) {
        if (!ext.Has(key)) return fallback;
        const tinygltf::Value& a = ext.Get(key);
        if (!a.IsArray() || a.ArrayLen() != 2) return fallback;
        return glm::dvec2(number(a.Get(0), fallback.x), number(a.Get(1), fallback.y));
    };
    const glm::dvec2 offset = pair("offset", {0.0, 0.0});
    const glm::dvec2 scale = pair("scale", {1.0, 1.0});
    const double rotation = ext.Has("rotation") ? number(ext.Get("rotation"), 0.0) : 0.0;
    const double c = std::cos(rotation), s = std::sin(rotation);
    const glm::dmat2 m = glm::dmat2(c, -s, s, c) * glm::dmat2(scale.x, 0.0, 0.0, scale.y);
    // igi's (u', v') = D g' + (0, 1) and g = D (u, v) + (0, 1), D = diag(1, -1).
    const glm::dmat2 d(1.0, 0.0, 0.0, -1.0);
    t.linear = glm::mat2(d * m * d);
    t.offset = glm::vec2(d * (m * glm::dvec2(0.0, 1.0) + offset) + glm::dvec2(0.0, 1.0));
    t.active = !(t.linear == glm::mat2(1.0f) && t.offset == glm::vec2(0.0f));
    return t;
}

glm::vec3 vec3Of(const std::vector<double>& v, glm::vec3 fallback) {
    if (v.size() < 3) return fallback;
    return {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
}

std::string extensionForMime(const std::string& mime) {
    if (mime == "image/png") return ".png";
    if (mime == "image/jpeg") return ".jpg";
    if (mime == "image/bmp") return ".bmp";
    if (mime == "image/gif") return ".gif";
    return ".png";
}

// ---- What the file uses that igi does not model -------------------------------------------

// Extensions whose content igi reads (KHR_lights_punctual's range is not modelled and
// KHR_materials_transmission's partial transmission is approximated, with warnings of their
// own). KHR_mesh_quantization's attribute types are read by AccessorReader, which refuses the
// ones it cannot read by name.
bool modelledExtension(const std::string& name) {
    static const std::set<std::string> kModelled = {
        "KHR_materials_emissive_strength", "KHR_materials_ior",
        "KHR_materials_transmission",      "KHR_lights_punctual",
        "KHR_mesh_quantization",           "KHR_texture_transform"};
    return kModelled.count(name) > 0;
}

std::string joined(const std::set<std::string>& names) {
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
    return out;
}

// A required extension that is not modelled is an error (the file says it cannot be shown
// without it); a used one, and every material feature igi does not render, is named in one
// warning per file, never dropped silently.
void checkGltfFeatures(const std::string& path, const tinygltf::Model& model) {
    std::set<std::string> required;
    for (const std::string& e : model.extensionsRequired)
        if (!modelledExtension(e)) required.insert(e);
    if (!required.empty())
        throw SceneError::atPath(path, "/extensionsRequired",
                                 "requires " + joined(required) + ", which igi does not support");
    std::set<std::string> used;
    for (const std::string& e : model.extensionsUsed)
        if (!modelledExtension(e)) used.insert(e);
    if (!used.empty())
        spdlog::warn("{}: extensions not modelled, rendered without them: {}", path, joined(used));
    std::set<std::string> ignored;
    // Which material and slot each of these concerns, so that the warning can be acted on.
    std::vector<std::string> otherTexCoord, partialTransmission;
    for (std::size_t i = 0; i < model.materials.size(); ++i) {
        const tinygltf::Material& m = model.materials[i];
        // Named as GltfMaterials::convert names it (and as scene files address it).
        const std::string name = "'" +
                                 (m.name.empty() ? std::filesystem::path(path).stem().string() +
                                                       "#material" + std::to_string(i)
                                                 : m.name) +
                                 "'";
        if (m.occlusionTexture.index >= 0)
            ignored.insert(
                "occlusionTexture (ambient occlusion is for rasterizers: a path tracer "
                "computes it)");
        const auto& pbr = m.pbrMetallicRoughness;
        // KHR_texture_transform is read for every slot; a texCoord other than 0, the
        // extension's or the slot's, is not: the lookup takes TEXCOORD_0 (igi's meshes carry
        // one set of uvs).
        const std::pair<const char*, const tinygltf::TextureInfo*> slots[] = {
            {"baseColorTexture", &pbr.baseColorTexture},
            {"metallicRoughnessTexture", &pbr.metallicRoughnessTexture},
            {"emissiveTexture", &m.emissiveTexture}};
        for (const auto& [slot, t] : slots)
            if (t->index >= 0 && texCoordOf(*t) != 0)
                otherTexCoord.push_back(name + " " + slot + " (texCoord " +
                                        std::to_string(texCoordOf(*t)) + ")");
        if (m.normalTexture.index >= 0 && texCoordOf(m.normalTexture) != 0)
            otherTexCoord.push_back(name + " normalTexture (texCoord " +
                                    std::to_string(texCoordOf(m.normalTexture)) + ")");
        // KHR_materials_transmission is all or nothing: above one half smooth glass, else
        // opaque metallic-roughness (GltfMaterials::convert). A factor strictly between 0 and
        // 1, or a transmissionTexture, is a material partly transmitting, which is not modelled.
        const double transmission =
            extensionNumber(m.extensions, "KHR_materials_transmission", "transmissionFactor", 0.0);
        const auto ext = m.extensions.find("KHR_materials_transmission");
        const bool textured = ext != m.extensions.end() && ext->second.Has("transmissionTexture");
        if ((transmission > 0.0 && transmission < 1.0) || textured) {
            char factor[32];
            std::snprintf(factor, sizeof factor, "%g", transmission);
            partialTransmission.push_back(
                name + " (factor " + factor + (textured ? ", transmissionTexture not read" : "") +
                ": rendered " + (transmission > 0.5 ? "as clear glass" : "opaque") + ")");
        }
        // A transmitting material's roughness is modelled: rough glass, the GGX BSDF of
        // Walter et al. (client/materials/RoughDielectric.h), smooth glass below the mirror
        // threshold (GltfMaterials::convert).
    }
    auto listed = [](const std::vector<std::string>& items) {
        std::string out;
        for (const std::string& item : items) out += (out.empty() ? "" : "; ") + item;
        return out;
    };
    if (!otherTexCoord.empty())
        ignored.insert("texCoord other than 0, TEXCOORD_0 read instead (" + listed(otherTexCoord) +
                       ")");
    if (!partialTransmission.empty())
        ignored.insert("partial KHR_materials_transmission, all or nothing instead (" +
                       listed(partialTransmission) + ")");
    // Lookups are bilinear, without mip-maps (a path tracer's pixels average many lookups):
    // a sampler that asks for nearest texels (pixel art, data maps) looks different.
    std::vector<std::string> nearest;
    for (std::size_t i = 0; i < model.samplers.size(); ++i) {
        const tinygltf::Sampler& s = model.samplers[i];
        if (s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST ||
            s.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST ||
            s.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST)
            nearest.push_back("sampler " + std::to_string(i));
    }
    if (!nearest.empty())
        ignored.insert("NEAREST texture filters, bilinear instead (" + listed(nearest) + ")");
    if (!ignored.empty())
        spdlog::warn("{}: material features not modelled, rendered without them: {}", path,
                     joined(ignored));
}

// ---- Materials ----------------------------------------------------------------------------

class GltfMaterials {
  public:
    GltfMaterials(const std::string& path, const tinygltf::Model& model, SceneAssets& assets)
        : path_(path), model_(model), assets_(assets) {}

    // Appends every material of the file; returns the scene index of the first.
    std::uint32_t appendAll() {
        assets_.checkMaterialCount(model_.materials.size(), path_);
        auto& materials = assets_.scene().materials;
        const auto base = static_cast<std::uint32_t>(materials.size());
        for (std::size_t i = 0; i < model_.materials.size(); ++i) {
            materials.push_back(convert(model_.materials[i], static_cast<int>(i)));
        }
        return base;
    }

  private:
    Material convert(const tinygltf::Material& gm, int index) {
        const auto& pbr = gm.pbrMetallicRoughness;
        Material m;
        m.name = gm.name.empty() ? std::filesystem::path(path_).stem().string() + "#material" +
                                       std::to_string(index)
                                 : gm.name;
        const glm::vec3 baseColor = glm::max(vec3Of(pbr.baseColorFactor, glm::vec3(1.0f)), 0.0f);
        m.emission = emission(gm);
        // Per texel (client/lights/EmissiveTexture.h); without a factor it emits nothing.
        if (gm.emissiveTexture.index >= 0 && m.isEmissive()) {
            m.emissionTexture = colourTexture(gm.emissiveTexture.index, "emissiveTexture");
            m.emissionUv = uvTransformOf(gm.emissiveTexture.extensions);
        }
        const double transmission =
            extensionNumber(gm.extensions, "KHR_materials_transmission", "transmissionFactor", 0.0);
        if (transmission > 0.5) {
            m.glass = true;
            const double ior = extensionNumber(gm.extensions, "KHR_materials_ior", "ior", 1.5);
            m.ior = ior > 0.0 ? static_cast<float>(ior) : 1.5f;
            // Rough glass (Material::glass with Reflection::Ggx) where the roughness factor
            // reaches the mirror threshold; the metallicRoughnessTexture's green scales it per
            // texel (texels under the threshold are smooth glass). Below it, smooth glass as
            // before: the texture only scales the factor down.
            const double roughness = std::clamp(pbr.roughnessFactor, 0.0, 1.0);
            if (roughness * roughness >= double(kMinGgxAlpha)) {
                m.reflection = Reflection::Ggx;
                m.roughness = static_cast<float>(roughness);
                m.metallic = 0.0f;
                if (pbr.metallicRoughnessTexture.index >= 0) {
                    m.metallicRoughnessTexture =
                        dataTexture(pbr.metallicRoughnessTexture.index, "metallicRoughnessTexture");
                    m.metallicRoughnessUv = uvTransformOf(pbr.metallicRoughnessTexture.extensions);
                }
            }
        } else {
            // Metallic-roughness (the specification's Appendix B). Without a
            // pbrMetallicRoughness both factors default to 1: a rough white metal.
            m.reflection = Reflection::Ggx;
            m.diffuse = baseColor;
            if (pbr.baseColorTexture.index >= 0) {
                m.diffuseTexture = colourTexture(pbr.baseColorTexture.index);
                m.diffuseUv = uvTransformOf(pbr.baseColorTexture.extensions);
            }
            m.roughness = static_cast<float>(std::clamp(pbr.roughnessFactor, 0.0, 1.0));
            m.metallic = static_cast<float>(std::clamp(pbr.metallicFactor, 0.0, 1.0));
            if (pbr.metallicRoughnessTexture.index >= 0) {
                m.metallicRoughnessTexture =
                    dataTexture(pbr.metallicRoughnessTexture.index, "metallicRoughnessTexture");
                m.metallicRoughnessUv = uvTransformOf(pbr.metallicRoughnessTexture.extensions);
            }
            const double ior = extensionNumber(gm.extensions, "KHR_materials_ior", "ior", 1.5);
            m.ior = ior >= 1.0 && std::isfinite(ior) ? static_cast<float>(ior) : 1.5f;
        }
        alphaOf(gm, m);
        // Tangent space, OpenGL's convention (green toward +v up the image), decoded linear.
        if (gm.normalTexture.index >= 0) {
            m.normalTexture = dataTexture(gm.normalTexture.index, "normalTexture");
            m.normalUv = uvTransformOf(gm.normalTexture.extensions);
            m.normalScale = std::isfinite(gm.normalTexture.scale)
                                ? static_cast<float>(gm.normalTexture.scale)
                                : 1.0f;
        }
        conserveEnergy(m, path_ + ": material '" + m.name + "'");
        return m;
    }

    // alphaMode MASK and BLEND: alpha is baseColorFactor's fourth component times the base
    // colour texture's alpha channel (COLOR_0's alpha is not read). OPAQUE ignores both.
    void alphaOf(const tinygltf::Material& gm, Material& m) {
        if (gm.alphaMode != "MASK" && gm.alphaMode != "BLEND") return;
        m.alphaMode = gm.alphaMode == "MASK" ? AlphaMode::Mask : AlphaMode::Blend;
        const auto& factor = gm.pbrMetallicRoughness.baseColorFactor;
        const double a = factor.size() == 4 ? factor[3] : 1.0;
        m.alpha = std::isfinite(a) ? static_cast<float>(std::clamp(a, 0.0, 1.0)) : 1.0f;
        m.alphaCutoff = std::isfinite(gm.alphaCutoff)
                            ? static_cast<float>(std::clamp(gm.alphaCutoff, 0.0, 1.0))
                            : 0.5f;
        const int texture = gm.pbrMetallicRoughness.baseColorTexture.index;
        if (texture >= 0) {
            m.alphaTexture = m.diffuseTexture >= 0 ? m.diffuseTexture : colourTexture(texture);
            m.alphaUv = uvTransformOf(gm.pbrMetallicRoughness.baseColorTexture.extensions);
        }
    }

    // emissiveFactor x KHR_materials_emissive_strength (the emissive texture multiplies it
    // per texel where the hit or the light sample is).
    glm::vec3 emission(const tinygltf::Material& gm) {
        const float strength = static_cast<float>(extensionNumber(
            gm.extensions, "KHR_materials_emissive_strength", "emissiveStrength", 1.0));
        return glm::max(vec3Of(gm.emissiveFactor, glm::vec3(0.0f)) * strength, 0.0f);
    }

    int imageOf(int textureIndex, const std::string& what) const {
        if (textureIndex < 0 || textureIndex >= static_cast<int>(model_.textures.size())) {
            throw SceneError::atPath(path_, "/textures/" + std::to_string(textureIndex),
                                     what + " refers to a texture that does not exist");
        }
        const int image = model_.textures[textureIndex].source;
        if (image < 0 || image >= static_cast<int>(model_.images.size())) {
            throw SceneError::atPath(path_, "/textures/" + std::to_string(textureIndex),
                                     "texture has no valid image source");
        }
        const auto& img = model_.images[image];
        if (img.image.empty()) {
            throw SceneError::atPath(path_, "/images/" + std::to_string(image),
                                     "image '" + img.uri + "' not found or unreadable");
        }
        return image;
    }

    // A name whose extension tells OpenImageIO the format, and the key that shares decodes.
    std::pair<std::string, std::string> imageNameAndKey(int image) const {
        const auto& img = model_.images[image];
        if (!img.uri.empty() && img.uri.rfind("data:", 0) != 0) {
            const std::string file = resolveRelative(path_, img.uri);
            return {file, file};
        }
        const std::string key = path_ + "#/images/" + std::to_string(image);
        return {key + extensionForMime(img.mimeType), key};
    }

    int colourTexture(int textureIndex, const std::string& what = "baseColorTexture") {
        return texture(textureIndex, what, TextureEncoding::Colour);
    }

    // A texture of values rather than colours: decoded without the sRGB curve.
    int dataTexture(int textureIndex, const std::string& what) {
        return texture(textureIndex, what, TextureEncoding::Data);
    }

    int texture(int textureIndex, const std::string& what, TextureEncoding encoding) {
        const int image = imageOf(textureIndex, what);
        const auto [name, key] = imageNameAndKey(image);
        const auto& bytes = model_.images[image].image;
        const auto [wrapU, wrapV] = wrapOf(textureIndex);
        return assets_.textureBytes(key, name, std::string(bytes.begin(), bytes.end()), encoding,
                                    wrapU, wrapV);
    }

    // The texture's sampler's wrapS and wrapT (REPEAT without a sampler, as the specification
    // says).
    std::pair<TextureWrap, TextureWrap> wrapOf(int textureIndex) const {
        const int sampler = model_.textures[textureIndex].sampler;
        if (sampler < 0) return {TextureWrap::Repeat, TextureWrap::Repeat};
        if (sampler >= static_cast<int>(model_.samplers.size()))
            throw SceneError::atPath(path_, "/textures/" + std::to_string(textureIndex),
                                     "sampler " + std::to_string(sampler) + " does not exist");
        const tinygltf::Sampler& s = model_.samplers[sampler];
        const std::string at = "/samplers/" + std::to_string(sampler);
        return {wrapMode(s.wrapS, at + "/wrapS"), wrapMode(s.wrapT, at + "/wrapT")};
    }

    TextureWrap wrapMode(int value, const std::string& at) const {
        switch (value) {
            case TINYGLTF_TEXTURE_WRAP_REPEAT:
                return TextureWrap::Repeat;
            case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE:
                return TextureWrap::ClampToEdge;
            case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT:
                return TextureWrap::MirroredRepeat;
            default:
                throw SceneError::atPath(path_, at,
                                         std::to_string(value) +
                                             " is not a wrap mode (10497 REPEAT, 33071 "
                                             "CLAMP_TO_EDGE, 33648 MIRRORED_REPEAT)");
        }
    }

    const std::string& path_;
    const tinygltf::Model& model_;
    SceneAssets& assets_;
};

// ---- Accessors ----------------------------------------------------------------------------

class AccessorReader {
  public:
    /// Accessors may have at most `maxCount` elements (SceneLimits::maxVertices).
    AccessorReader(const std::string& path, const tinygltf::Model& model, std::uint64_t maxCount)
        : path_(path), model_(model), maxCount_(maxCount) {}

    // count x components floats; integer components must be normalized (e.g. texcoords).
    std::vector<float> floats(int index, int type) const {
        const tinygltf::Accessor& acc = accessor(index);
        const int components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(type));
        if (acc.type != type) fail(index, "unexpected accessor type");
        if (acc.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !acc.normalized) {
            fail(index, "expected float or normalized integer components");
        }
        // Checked against the buffer before allocating for the count it claims.
        const Elements elements = elementsOf(index);
        std::vector<float> out(acc.count * components, 0.0f);
        elements.forEach([&](std::size_t i, const unsigned char* p) {
            for (int c = 0; c < components; ++c) out[i * components + c] = component(acc, p, c);
        });
        return out;
    }

    std::vector<std::uint32_t> indices(int index) const {
        const tinygltf::Accessor& acc = accessor(index);
        if (acc.type != TINYGLTF_TYPE_SCALAR) fail(index, "indices must be scalars");
        if (acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
            acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
            fail(index, "indices must be unsigned integers");
        }
        const Elements elements = elementsOf(index);
        std::vector<std::uint32_t> out(acc.count, 0);
        elements.forEach([&](std::size_t i, const unsigned char* p) {
            switch (acc.componentType) {
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
                    out[i] = *p;
                    break;
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
                    out[i] = load<std::uint16_t>(p);
                    break;
                default:
                    out[i] = load<std::uint32_t>(p);
                    break;
            }
        });
        return out;
    }

    std::size_t count(int index) const { return accessor(index).count; }
    int type(int index) const { return accessor(index).type; }

  private:
    // Where an accessor's elements are in its buffer, checked to lie inside it.
    struct Elements {
        const unsigned char* first = nullptr;  // nullptr: no buffer view, all zeros
        std::size_t stride = 0;
        std::size_t count = 0;

        template <typename Visit>
        void forEach(Visit visit) const {
            if (!first) return;
            for (std::size_t i = 0; i < count; ++i) visit(i, first + i * stride);
        }
    };

    template <typename T>
    static T load(const unsigned char* p) {
        T v;
        std::memcpy(&v, p, sizeof v);
        return v;
    }

    [[noreturn]] void fail(int index, const std::string& message) const {
        throw SceneError::atPath(path_, "/accessors/" + std::to_string(index), message);
    }

    const tinygltf::Accessor& accessor(int index) const {
        if (index < 0 || index >= static_cast<int>(model_.accessors.size())) {
            fail(index, "accessor does not exist");
        }
        const auto& acc = model_.accessors[index];
        if (acc.sparse.isSparse) fail(index, "sparse accessors are not supported");
        // An accessor without a buffer view is all zeros: only this bounds its count.
        if (acc.count > maxCount_) {
            fail(index, "count " + std::to_string(acc.count) + " is over the limit of " +
                            std::to_string(maxCount_));
        }
        return acc;
    }

    static float component(const tinygltf::Accessor& acc, const unsigned char* p, int c) {
        switch (acc.componentType) {
            case TINYGLTF_COMPONENT_TYPE_FLOAT:
                return load<float>(p + 4 * c);
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
                return p[c] / 255.0f;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
                return load<std::uint16_t>(p + 2 * c) / 65535.0f;
            case TINYGLTF_COMPONENT_TYPE_BYTE:
                return std::max(static_cast<signed char>(p[c]) / 127.0f, -1.0f);
            case TINYGLTF_COMPONENT_TYPE_SHORT:
                return std::max(load<std::int16_t>(p + 2 * c) / 32767.0f, -1.0f);
            default:
                return 0.0f;
        }
    }

    // Checks that every element lies inside its buffer view and buffer, in arithmetic that a
    // hostile offset or count near 2^64 cannot wrap around.
    Elements elementsOf(int index) const {
        const tinygltf::Accessor& acc = accessor(index);
        if (acc.bufferView < 0 || acc.count == 0) return {};
        if (acc.bufferView >= static_cast<int>(model_.bufferViews.size()))
            fail(index, "buffer view does not exist");
        const tinygltf::BufferView& view = model_.bufferViews[acc.bufferView];
        if (view.buffer < 0 || view.buffer >= static_cast<int>(model_.buffers.size()))
            fail(index, "buffer does not exist");
        const auto& data = model_.buffers[view.buffer].data;
        const int stride = acc.ByteStride(view);
        const int elementSize =
            tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(acc.componentType)) *
            tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(acc.type));
        if (stride <= 0 || elementSize <= 0) fail(index, "invalid component type or stride");
        if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
            fail(index, "its buffer view reaches past the end of its buffer");
        if (acc.byteOffset > view.byteLength)
            fail(index, "accessor reaches past the end of its buffer");
        const std::size_t available = view.byteLength - acc.byteOffset;
        if (static_cast<std::size_t>(elementSize) > available ||
            acc.count - 1 > (available - elementSize) / static_cast<std::size_t>(stride)) {
            fail(index, "accessor reaches past the end of its buffer");
        }
        return {data.data() + view.byteOffset + acc.byteOffset, static_cast<std::size_t>(stride),
                acc.count};
    }

    const std::string& path_;
    const tinygltf::Model& model_;
    std::uint64_t maxCount_;
};

// ---- Geometry -----------------------------------------------------------------------------

glm::dmat4 localMatrix(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) return glm::make_mat4(node.matrix.data());
    glm::dmat4 m(1.0);
    if (node.translation.size() == 3)
        m = glm::translate(m, glm::make_vec3(node.translation.data()));
    if (node.rotation.size() == 4) {
        const auto& r = node.rotation;  // glTF stores x, y, z, w
        m = m * glm::mat4_cast(glm::normalize(glm::dquat(r[3], r[0], r[1], r[2])));
    }
    if (node.scale.size() == 3) m = glm::scale(m, glm::make_vec3(node.scale.data()));
    return m;
}

// Triangle corner indices of a primitive in list, strip or fan mode.
std::vector<glm::uvec3> assembleTriangles(int mode, const std::vector<std::uint32_t>& idx) {
    std::vector<glm::uvec3> tris;
    const std::size_t n = idx.size();
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        for (std::size_t i = 0; i + 2 < n; i += 3)
            tris.emplace_back(idx[i], idx[i + 1], idx[i + 2]);
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        for (std::size_t i = 0; i + 2 < n; ++i) {
            if (i % 2 == 0) {
                tris.emplace_back(idx[i], idx[i + 1], idx[i + 2]);
            } else {
                tris.emplace_back(idx[i + 1], idx[i], idx[i + 2]);
            }
        }
    } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
        for (std::size_t i = 1; i + 1 < n; ++i) tris.emplace_back(idx[0], idx[i], idx[i + 1]);
    }
    return tris;
}

class GltfFlattener {
  public:
    GltfFlattener(const std::string& path, const tinygltf::Model& model, std::uint32_t materialBase,
                  SceneAssets& assets, Mesh& mesh, std::vector<PunctualLight>& lights,
                  std::vector<GltfInstances>* instances)
        : path_(path),
          model_(model),
          accessors_(path, model, assets.limits().maxVertices),
          materialBase_(materialBase),
          assets_(assets),
          mesh_(mesh),
          lights_(lights),
          instances_(instances),
          visited_(model.nodes.size(), false) {
        for (const auto& m : model.meshes) {
            for (const auto& p : m.primitives) {
                withNormals_ = withNormals_ || p.attributes.count("NORMAL") > 0;
                withUvs_ = withUvs_ || p.attributes.count("TEXCOORD_0") > 0;
                withTangents_ = withTangents_ || p.attributes.count("TANGENT") > 0;
                withColours_ = withColours_ || p.attributes.count("COLOR_0") > 0;
            }
        }
    }

    // The nodes' meshes are placed after the whole tree is read, so that a primitive placed by
    // several nodes is known as such at its first placement.
    void run() {
        for (int root : rootNodes()) visit(root, glm::dmat4(1.0), 0);
        if (instances_) countPlacements();
        for (const auto& [meshIndex, world] : placements_) addMesh(meshIndex, world);
    }

  private:
    std::vector<int> rootNodes() const {
        const int scene =
            model_.defaultScene >= 0 ? model_.defaultScene : (model_.scenes.empty() ? -1 : 0);
        if (scene >= 0 && scene < static_cast<int>(model_.scenes.size()))
            return model_.scenes[scene].nodes;
        // No scene: every node that is nobody's child.
        std::vector<bool> isChild(model_.nodes.size(), false);
        for (const auto& n : model_.nodes) {
            for (int c : n.children) {
                if (c >= 0 && c < static_cast<int>(isChild.size())) isChild[c] = true;
            }
        }
        std::vector<int> roots;
        for (std::size_t i = 0; i < isChild.size(); ++i) {
            if (!isChild[i]) roots.push_back(static_cast<int>(i));
        }
        return roots;
    }

    void visit(int index, const glm::dmat4& parent, int depth) {
        const std::string where = "/nodes/" + std::to_string(index);
        if (index < 0 || index >= static_cast<int>(model_.nodes.size())) {
            throw SceneError::atPath(path_, where, "node does not exist");
        }
        if (depth > kMaxNodeDepth)
            throw SceneError::atPath(path_, where, "node hierarchy too deep (a cycle?)");
        // glTF nodes form disjoint trees. A node reached twice would be a cycle, or a graph
        // whose paths multiply with its depth (2^256 visits for a chain of pairs).
        if (visited_[index]) {
            throw SceneError::atPath(path_, where,
                                     "node is reached twice (glTF nodes must form trees)");
        }
        visited_[index] = true;
        const tinygltf::Node& node = model_.nodes[index];
        const glm::dmat4 world = parent * localMatrix(node);
        if (node.mesh >= 0) placements_.emplace_back(node.mesh, world);
        addLight(node, world, where);
        for (int child : node.children) visit(child, world, depth + 1);
    }

    void addLight(const tinygltf::Node& node, const glm::dmat4& world, const std::string& where) {
        auto ext = node.extensions.find("KHR_lights_punctual");
        if (ext == node.extensions.end() || !ext->second.Has("light")) return;
        const int index = ext->second.Get("light").GetNumberAsInt();
        if (index < 0 || index >= static_cast<int>(model_.lights.size())) {
            throw SceneError::atPath(
                path_, where,
                "KHR_lights_punctual light " + std::to_string(index) + " does not exist");
        }
        const tinygltf::Light& gl = model_.lights[index];
        PunctualLight light;
        light.name = gl.name.empty() ? "light" + std::to_string(index) : gl.name;
        light.position = glm::vec3(world * glm::dvec4(0.0, 0.0, 0.0, 1.0));
        // Spot and directional lights shine down the node's local -Z.
        const glm::dvec3 axis = glm::dvec3(world * glm::dvec4(0.0, 0.0, -1.0, 0.0));
        if (glm::length(axis) > 0.0) light.direction = glm::vec3(glm::normalize(axis));
        // The specification's photometric units (candela, lux) become radiometric ones with
        // the luminous efficacy 683 lm/W, as Blender's importer does in its default lighting
        // mode (Standard): W/sr = cd / 683, W/m^2 = lux / 683 (docs/SCENE_FORMAT.md, "glTF").
        const glm::vec3 colour = glm::max(vec3Of(gl.color, glm::vec3(1.0f)), 0.0f);
        light.intensity = colour * static_cast<float>(std::max(gl.intensity, 0.0) / kLumensPerWatt);
        if (gl.type == "directional") {
            light.kind = LightKind::Directional;
        } else if (gl.type == "spot") {
            light.kind = LightKind::Spot;
            light.outerDeg =
                static_cast<float>(std::clamp(glm::degrees(gl.spot.outerConeAngle), 1e-3, 90.0));
            light.innerDeg = static_cast<float>(
                std::clamp(glm::degrees(gl.spot.innerConeAngle), 0.0, double(light.outerDeg)));
        } else if (gl.type != "point") {
            spdlog::warn("{}: light '{}' has the unknown type '{}': ignored", path_, light.name,
                         gl.type);
            return;
        }
        if (gl.range > 0.0 && !warnedRange_) {
            // Blender's importer ignores it too; a light that stops at a distance is not
            // physical and not modelled.
            spdlog::warn(
                "{}: light '{}' has a range ({}): not modelled, its light reaches "
                "further",
                path_, light.name, gl.range);
            warnedRange_ = true;
        }
        lights_.push_back(light);
    }

    void addMesh(int meshIndex, const glm::dmat4& world) {
        if (meshIndex >= static_cast<int>(model_.meshes.size())) {
            throw SceneError::atPath(path_, "/meshes/" + std::to_string(meshIndex),
                                     "mesh does not exist");
        }
        const auto& primitives = model_.meshes[meshIndex].primitives;
        for (std::size_t p = 0; p < primitives.size(); ++p) {
            const std::string where =
                "/meshes/" + std::to_string(meshIndex) + "/primitives/" + std::to_string(p);
            auto shared = sharedIndex_.find(primitiveKey(primitives[p]));
            if (instanceable(primitives[p], world) && shared != sharedIndex_.end()) {
                addInstance(primitives[p], world, where, shared->second);
            } else {
                addPrimitive(primitives[p], world, where, mesh_);
            }
        }
    }

    // What makes two primitives the same geometry: their mode and accessors.
    using PrimitiveKey = std::array<int, 7>;
    PrimitiveKey primitiveKey(const tinygltf::Primitive& prim) const {
        return {prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode,
                attribute(prim, "POSITION"),
                nonEmpty(attribute(prim, "NORMAL")),
                nonEmpty(attribute(prim, "TEXCOORD_0")),
                nonEmpty(attribute(prim, "TANGENT")),
                nonEmpty(attribute(prim, "COLOR_0")),
                prim.indices};
    }

    // Whether a placement of `prim` may be an instance: a triangle primitive of an opaque
    // material (cut-outs stay per triangle in the flattened mesh) placed by a matrix that does
    // not mirror (the loader turns a mirrored primitive's triangles; an instance would not).
    bool instanceable(const tinygltf::Primitive& prim, const glm::dmat4& world) const {
        const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
        if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
            mode != TINYGLTF_MODE_TRIANGLE_FAN)
            return false;
        if (attribute(prim, "POSITION") < 0) return false;
        if (prim.material >= 0 && prim.material < static_cast<int>(model_.materials.size())) {
            const std::string& alpha = model_.materials[prim.material].alphaMode;
            if (!alpha.empty() && alpha != "OPAQUE") return false;
        }
        return glm::determinant(glm::dmat3(world)) > 0.0;
    }

    // The primitives placed (instanceable) by at least two nodes get an entry of instances_
    // (primitives of one mesh that share accessors, as with a material each, are not placed
    // twice: one node).
    void countPlacements() {
        std::map<PrimitiveKey, int> count;
        for (const auto& [meshIndex, world] : placements_) {
            if (meshIndex < 0 || meshIndex >= static_cast<int>(model_.meshes.size())) continue;
            std::set<PrimitiveKey> keys;
            for (const auto& prim : model_.meshes[meshIndex].primitives)
                if (instanceable(prim, world)) keys.insert(primitiveKey(prim));
            for (const PrimitiveKey& key : keys) ++count[key];
        }
        for (const auto& [key, n] : count) {
            if (n < 2) continue;
            sharedIndex_[key] = instances_->size();
            instances_->emplace_back();
        }
    }

    // A placement of a shared primitive: its geometry read at the first (in its own space), the
    // node's matrix and material each time. The scene is charged as for a flattened copy.
    void addInstance(const tinygltf::Primitive& prim, const glm::dmat4& world,
                     const std::string& where, std::size_t shared) {
        GltfInstances& out = (*instances_)[shared];
        if (out.placements.empty()) {
            addPrimitive(prim, glm::dmat4(1.0), where, out.geometry);
        } else {
            const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
            const int nAcc = nonEmpty(attribute(prim, "NORMAL"));
            chargeGeometry(prim, mode, accessors_.count(attribute(prim, "POSITION")), nAcc < 0,
                           where);
        }
        out.placements.push_back({glm::mat4(world), materialId(prim.material)});
    }

    std::uint32_t materialId(int material) {
        if (material >= 0 && material < static_cast<int>(model_.materials.size())) {
            return materialBase_ + static_cast<std::uint32_t>(material);
        }
        if (!defaultId_) {
            defaultId_ = static_cast<std::uint32_t>(assets_.scene().materials.size());
            assets_.scene().materials.push_back(defaultMaterial());
        }
        return *defaultId_;
    }

    int attribute(const tinygltf::Primitive& prim, const char* name) const {
        auto it = prim.attributes.find(name);
        return it == prim.attributes.end() ? -1 : it->second;
    }

    int nonEmpty(int accessor) const {
        return accessor >= 0 && accessors_.count(accessor) == 0 ? -1 : accessor;
    }

    void addPrimitive(const tinygltf::Primitive& prim, const glm::dmat4& world,
                      const std::string& where, Mesh& target) {
        const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
        if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
            mode != TINYGLTF_MODE_TRIANGLE_FAN) {
            spdlog::warn("{}: {}: points and lines are not rendered", path_, where);
            return;
        }
        const int posAccessor = attribute(prim, "POSITION");
        if (posAccessor < 0) throw SceneError::atPath(path_, where, "primitive has no POSITION");
        // An attribute with no elements counts as absent.
        const int nAcc = nonEmpty(attribute(prim, "NORMAL"));
        const int tAcc = nonEmpty(attribute(prim, "TEXCOORD_0"));
        const int tanAcc = nonEmpty(attribute(prim, "TANGENT"));
        const int colAcc = nonEmpty(attribute(prim, "COLOR_0"));
        const std::size_t count = accessors_.count(posAccessor);
        // Compared before reading: neither is read when it claims more than POSITION.
        if (nAcc >= 0 && accessors_.count(nAcc) != count)
            throw SceneError::atPath(path_, where, "NORMAL count differs from POSITION");
        if (tAcc >= 0 && accessors_.count(tAcc) != count)
            throw SceneError::atPath(path_, where, "TEXCOORD_0 count differs from POSITION");
        if (tanAcc >= 0 && accessors_.count(tanAcc) != count)
            throw SceneError::atPath(path_, where, "TANGENT count differs from POSITION");
        if (colAcc >= 0 && accessors_.count(colAcc) != count)
            throw SceneError::atPath(path_, where, "COLOR_0 count differs from POSITION");
        chargeGeometry(prim, mode, count, nAcc < 0, where);

        const std::vector<float> pos = accessors_.floats(posAccessor, TINYGLTF_TYPE_VEC3);
        for (float v : pos) {
            if (!std::isfinite(v)) throw SceneError::atPath(path_, where, "POSITION is not finite");
        }
        std::vector<std::uint32_t> idx;
        if (prim.indices >= 0) {
            idx = accessors_.indices(prim.indices);
        } else {
            idx.resize(count);
            for (std::size_t i = 0; i < count; ++i) idx[i] = static_cast<std::uint32_t>(i);
        }
        for (std::uint32_t i : idx) {
            if (i >= count)
                throw SceneError::atPath(path_, where,
                                         "index " + std::to_string(i) + " is out of range");
        }
        Attributes attr{
            pos, nAcc >= 0 ? accessors_.floats(nAcc, TINYGLTF_TYPE_VEC3) : std::vector<float>(),
            tAcc >= 0 ? accessors_.floats(tAcc, TINYGLTF_TYPE_VEC2) : std::vector<float>(),
            tanAcc >= 0 ? accessors_.floats(tanAcc, TINYGLTF_TYPE_VEC4) : std::vector<float>(),
            colAcc >= 0 ? colours(colAcc, prim.material, where) : std::vector<float>()};
        emit(assembleTriangles(mode, idx), attr, world, materialId(prim.material), target);
    }

    // Charges the scene with the primitive's triangles and the vertices emit() will add,
    // before anything of that size is read or allocated.
    void chargeGeometry(const tinygltf::Primitive& prim, int mode, std::size_t count,
                        bool noNormals, const std::string& where) {
        const std::uint64_t corners = prim.indices >= 0 ? accessors_.count(prim.indices) : count;
        const std::uint64_t triangles = mode == TINYGLTF_MODE_TRIANGLES ? corners / 3
                                        : corners >= 2                  ? corners - 2
                                                                        : 0;
        // A flat-shaded primitive gets three vertices per triangle.
        const std::uint64_t vertices = withNormals_ && noNormals ? 3 * triangles : count;
        Budget& t = assets_.triangles();
        Budget& v = assets_.vertices();
        if (!t.fits(triangles)) throw SceneError::atPath(path_, where, t.exceeded(triangles));
        if (!v.fits(vertices)) throw SceneError::atPath(path_, where, v.exceeded(vertices));
        t.add(triangles);
        v.add(vertices);
    }

    struct Attributes {
        std::vector<float> positions, normals, uvs, tangents;
        std::vector<float> colours;  ///< RGB, 3 per vertex (COLOR_0's alpha dropped)
    };

    // COLOR_0 as RGB (linear; float, or normalized unsigned byte or short, as the specification
    // allows), which multiplies the base colour. Its alpha is not read: where the material is
    // MASK or BLEND and some alpha is below one, one warning per file says so.
    std::vector<float> colours(int accessor, int material, const std::string& where) {
        const int type = accessors_.type(accessor);
        if (type != TINYGLTF_TYPE_VEC3 && type != TINYGLTF_TYPE_VEC4)
            throw SceneError::atPath(path_, where + "/attributes/COLOR_0",
                                     "COLOR_0 must be a VEC3 or VEC4 accessor");
        const std::vector<float> values = accessors_.floats(accessor, type);
        const std::size_t n = type == TINYGLTF_TYPE_VEC4 ? 4 : 3;
        std::vector<float> rgb;
        rgb.reserve(values.size() / n * 3);
        bool translucent = false;
        for (std::size_t i = 0; i + n <= values.size(); i += n) {
            for (std::size_t c = 0; c < 3; ++c) {
                if (!std::isfinite(values[i + c]))
                    throw SceneError::atPath(path_, where + "/attributes/COLOR_0",
                                             "COLOR_0 is not finite");
                rgb.push_back(std::max(values[i + c], 0.0f));
            }
            translucent = translucent || (n == 4 && values[i + 3] < 1.0f);
        }
        const bool covers = material >= 0 && material < static_cast<int>(model_.materials.size()) &&
                            model_.materials[material].alphaMode != "OPAQUE" &&
                            !model_.materials[material].alphaMode.empty();
        if (translucent && covers && !warnedColourAlpha_) {
            spdlog::warn(
                "{}: {}: COLOR_0's alpha is not modelled: coverage is baseColorFactor's "
                "and the base colour texture's alpha alone",
                path_, where);
            warnedColourAlpha_ = true;
        }
        return rgb;
    }

    // Appends the triangles, transformed to the file's space. A primitive without normals in a
    // mesh that has them is flat-shaded (glTF's rule): its triangles get vertices of their own,
    // and no tangents (the specification ignores them without normals). A vertex without a
    // tangent, in a mesh that has some, gets (0, 0, 0, 0): its frame comes from the uvs.
    void emit(const std::vector<glm::uvec3>& tris, const Attributes& a, const glm::dmat4& world,
              std::uint32_t material, Mesh& out) {
        const glm::mat4 m(world);
        const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(m)));
        const bool flip = glm::determinant(glm::mat3(m)) < 0.0f;
        const bool flat = withNormals_ && a.normals.empty();
        const auto base = static_cast<std::uint32_t>(out.positions.size());
        auto pushVertex = [&](std::uint32_t i, glm::vec3 flatNormal) {
            out.positions.push_back(
                glm::vec3(m * glm::vec4(a.positions[3 * i], a.positions[3 * i + 1],
                                        a.positions[3 * i + 2], 1.0f)));
            if (withNormals_) {
                glm::vec3 n = flat
                                  ? flatNormal
                                  : normalMatrix * glm::vec3(a.normals[3 * i], a.normals[3 * i + 1],
                                                             a.normals[3 * i + 2]);
                const float len = glm::length(n);
                out.normals.push_back(len > 0.0f && std::isfinite(len) ? n / len : flatNormal);
            }
            if (withTangents_)
                out.tangents.push_back(flat ? glm::vec4(0.0f) : tangent(a, i, m, flip));
            // A vertex without COLOR_0, in a mesh that has some, is white.
            if (withColours_)
                out.colors.push_back(
                    a.colours.empty()
                        ? glm::vec3(1.0f)
                        : glm::vec3(a.colours[3 * i], a.colours[3 * i + 1], a.colours[3 * i + 2]));
            // glTF's v runs down the image, igi's (OBJ's) up.
            if (withUvs_)
                out.uvs.push_back(a.uvs.empty() ? glm::vec2(0.0f)
                                                : glm::vec2(a.uvs[2 * i], 1.0f - a.uvs[2 * i + 1]));
        };
        if (!flat) {
            for (std::size_t i = 0; i < a.positions.size() / 3; ++i)
                pushVertex(static_cast<std::uint32_t>(i), glm::vec3(0, 0, 1));
        }
        for (const glm::uvec3& t : tris) {
            glm::uvec3 corners = t + glm::uvec3(base);
            if (flat) {
                const auto first = static_cast<std::uint32_t>(out.positions.size());
                const glm::vec3 n = faceNormal(a, t, m, flip);
                for (int c = 0; c < 3; ++c) pushVertex(t[c], n);
                corners = glm::uvec3(first, first + 1, first + 2);
            }
            if (flip) std::swap(corners.y, corners.z);
            out.triangles.push_back(corners);
            out.materialIds.push_back(material);
        }
    }

    // A tangent is a direction in the surface: it goes by the matrix (not the normal matrix).
    // The bitangent, cross(normal, tangent) * w, must be the image of the file's: where the
    // matrix mirrors, cross(M n, M t) is minus the image of cross(n, t), so w changes sign.
    static glm::vec4 tangent(const Attributes& a, std::uint32_t i, const glm::mat4& m, bool flip) {
        if (a.tangents.empty()) return glm::vec4(0.0f);
        const glm::vec3 t = glm::mat3(m) * glm::vec3(a.tangents[4 * i], a.tangents[4 * i + 1],
                                                     a.tangents[4 * i + 2]);
        const float w = a.tangents[4 * i + 3];
        const float len = glm::length(t);
        if (!(len > 0.0f) || !std::isfinite(len) || !std::isfinite(w)) return glm::vec4(0.0f);
        const float sign = (w < 0.0f) != flip ? -1.0f : 1.0f;
        return glm::vec4(t / len, sign);
    }

    static glm::vec3 faceNormal(const Attributes& a, glm::uvec3 t, const glm::mat4& m, bool flip) {
        auto p = [&](std::uint32_t i) {
            return glm::vec3(m * glm::vec4(a.positions[3 * i], a.positions[3 * i + 1],
                                           a.positions[3 * i + 2], 1.0f));
        };
        glm::vec3 n = glm::cross(p(t.y) - p(t.x), p(t.z) - p(t.x));
        if (flip) n = -n;
        const float len = glm::length(n);
        return len > 0.0f && std::isfinite(len) ? n / len : glm::vec3(0, 0, 1);
    }

    const std::string& path_;
    const tinygltf::Model& model_;
    AccessorReader accessors_;
    std::uint32_t materialBase_;
    SceneAssets& assets_;
    Mesh& mesh_;
    std::vector<PunctualLight>& lights_;
    std::vector<GltfInstances>* instances_;               ///< null: every placement flattened
    std::vector<std::pair<int, glm::dmat4>> placements_;  ///< (mesh, node matrix), in tree order
    std::map<PrimitiveKey, std::size_t> sharedIndex_;     ///< into instances_
    bool warnedRange_ = false;  ///< one warning per file for lights with a range
    std::vector<bool> visited_;
    bool withNormals_ = false;
    bool withUvs_ = false;
    bool withTangents_ = false;
    bool withColours_ = false;
    bool warnedColourAlpha_ = false;  ///< one warning per file for COLOR_0's alpha
    std::optional<std::uint32_t> defaultId_;
};

}  // namespace

void loadGltf(const std::string& path, SceneAssets& assets, Mesh& mesh,
              std::vector<PunctualLight>& lights, std::vector<GltfInstances>* instances) {
    const tinygltf::Model model = parseGltf(path, assets);
    checkGltfFeatures(path, model);
    const std::uint32_t base = GltfMaterials(path, model, assets).appendAll();
    GltfFlattener(path, model, base, assets, mesh, lights, instances).run();
    spdlog::debug("{}: {} triangles, {} materials, {} lights", path, mesh.triangles.size(),
                  model.materials.size(), lights.size());
}

}  // namespace igi
