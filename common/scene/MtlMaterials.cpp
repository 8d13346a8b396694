#include "scene/MtlMaterials.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <utility>

#include <spdlog/spdlog.h>

#include "scene/BumpMapKind.h"
#include "scene/ObjText.h"
#include "scene/SceneError.h"
#include "scene/TextureLoader.h"

namespace igi {

namespace {

// Above this Phong exponent a lobe is narrower than a pixel at any sensible resolution:
// treat it as a mirror (the Cornell sphere's mirror ball says Ns 1000).
constexpr float kMirrorPhongExponent = 1000.0f;
constexpr float kDefaultGlassIor = 1.5f;

glm::vec3 rgb(const tinyobj::real_t* c) {
    glm::vec3 v(static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2]));
    // tinyobjloader reads what it cannot parse as 0; negative colours mean nothing.
    return glm::max(v, glm::vec3(0.0f));
}

float maxComponent(glm::vec3 v) {
    return std::max({v.x, v.y, v.z});
}

void applyIllum(const tinyobj::material_t& mtl, const std::string& where, Material& m) {
    switch (mtl.illum) {
        case 3:  // reflection on, ray traced
        case 5:  // reflection with Fresnel
            m.reflection = Reflection::Mirror;
            return;
        case 4:  // glass, ray-traced reflection
        case 6:  // refraction
        case 7:  // refraction with Fresnel
            m.glass = true;
            // Tf is not used: exporters write it inconsistently (the Cornell sphere's clear
            // glass says Tf 0.1); a scene file can set "transmittance".
            if (mtl.ior > 1.0f) {
                m.ior = static_cast<float>(mtl.ior);
            } else {
                spdlog::warn("{}: glass without a usable Ni ({}): using an index of {}", where,
                             mtl.ior, kDefaultGlassIor);
                m.ior = kDefaultGlassIor;
            }
            return;
        default:
            // illum 2 (highlights on) is what exporters write for everything: a glossy lobe
            // only if Ks says so.
            if (mtl.illum == 2 && maxComponent(m.specular) > 0.0f) {
                m.reflection = m.phongExponent >= kMirrorPhongExponent ? Reflection::Mirror
                                                                       : Reflection::Glossy;
            }
            return;
    }
}

// The statement that named the bump map, for messages: tinyobjloader takes any of the three.
std::string bumpStatement(const std::string& mtlText, const std::string& material) {
    const int newmtl = mtlLine(mtlText, material, "newmtl");
    for (const char* keyword : {"map_bump", "map_Bump", "bump"})
        if (mtlLine(mtlText, material, keyword) != newmtl) return keyword;
    return "bump";
}

std::string slashes(std::string name) {
    std::replace(name.begin(), name.end(), '\\', '/');
    return name;
}

}  // namespace

FileSourceMtlReader::FileSourceMtlReader(FileSource& files, std::string objPath,
                                         std::size_t maxMaterials, std::size_t sceneMaterials)
    : files_(files),
      objPath_(std::move(objPath)),
      maxMaterials_(maxMaterials),
      sceneMaterials_(sceneMaterials) {}

std::string FileSourceMtlReader::problem(const std::string& library) const {
    auto it = problems_.find(library);
    return it == problems_.end() ? std::string() : it->second;
}

void FileSourceMtlReader::addPlaceholders(const std::string& library,
                                          const std::vector<std::string>& names) {
    if (names.size() > maxMaterials_ ||
        sceneMaterials_ + materialFiles_.size() > maxMaterials_ - names.size())
        throw SceneError::inFile(objPath_, std::to_string(names.size()) +
                                               " materials that no library defines would exceed "
                                               "the limit of " +
                                               std::to_string(maxMaterials_) + " per scene");
    std::string text;
    const Material d = defaultMaterial();
    for (const std::string& name : names)
        text += "newmtl " + name + "\nKd " + std::to_string(d.diffuse.x) + " " +
                std::to_string(d.diffuse.y) + " " + std::to_string(d.diffuse.z) + "\n";
    placeholders_[library] = text;
}

void FileSourceMtlReader::restart() {
    missing_.clear();
    problems_.clear();
    libraries_.clear();
    materialFiles_.clear();
}

bool FileSourceMtlReader::operator()(const std::string& matId,
                                     std::vector<tinyobj::material_t>* materials,
                                     std::map<std::string, int>* matMap, std::string* warn,
                                     std::string* err) {
    if (auto it = placeholders_.find(matId); it != placeholders_.end()) {
        texts_[matId] = it->second;
        std::istringstream stream(it->second);
        tinyobj::LoadMtl(matMap, materials, &stream, warn, err);
        materialFiles_.resize(materials->size(), matId);
        return true;
    }
    try {
        const std::string resolved = resolveRelative(objPath_, slashes(matId));
        files_.checkPath(resolved);
        const auto path = locateFile(files_, resolved);
        if (!path) {
            missing_.push_back(matId);
            return false;
        }
        const std::string& text = texts_[*path] = files_.read(*path);
        // tinyobjloader allocates 2 kB per material: count them first.
        const std::size_t count = countNewmtl(text);
        const std::size_t have = sceneMaterials_ + materials->size();
        if (count > maxMaterials_ || have > maxMaterials_ - count) {
            throw SceneError::inFile(*path, std::to_string(count) +
                                                " more materials would exceed the limit of " +
                                                std::to_string(maxMaterials_) + " per scene (" +
                                                std::to_string(have) + " already)");
        }
        std::istringstream stream(text);
        tinyobj::LoadMtl(matMap, materials, &stream, warn, err);
        materialFiles_.resize(materials->size(), *path);
        libraries_.push_back(*path);
        return true;
    } catch (const SceneError& e) {
        // Never let an exception cross tinyobjloader's frames.
        missing_.push_back(matId);
        problems_[matId] = e.message();
        if (err) *err += e.what();
        return false;
    } catch (const std::exception& e) {
        missing_.push_back(matId);
        problems_[matId] = e.what();
        if (err) *err += e.what();
        return false;
    }
}

Material defaultMaterial() {
    Material m;
    m.name = "default";
    m.diffuse = glm::vec3(0.8f);
    return m;
}

void conserveEnergy(Material& m, const std::string& where) {
    if (m.glass) return;
    const glm::vec3 total =
        m.diffuse + (m.reflection == Reflection::None || m.reflection == Reflection::Ggx
                         ? glm::vec3(0.0f)
                         : m.specular);  // GGX's f0 comes from metallic and ior, not specular
    const float peak = maxComponent(total);
    if (peak <= 1.0f) return;
    spdlog::warn("{}: diffuse + specular reflects {:.3g} > 1 of the light: scaled down", where,
                 peak);
    m.diffuse /= peak;
    m.specular /= peak;
}

Material materialFromMtl(const tinyobj::material_t& mtl, const std::string& mtlPath,
                         const std::string& mtlText, SceneAssets& assets) {
    const std::string where = mtlPath + ": material '" + mtl.name + "'";
    Material m;
    m.name = mtl.name;
    m.diffuse = rgb(mtl.diffuse);
    m.specular = rgb(mtl.specular);
    m.emission = rgb(mtl.emission);
    m.phongExponent = std::max(0.0f, static_cast<float>(mtl.shininess));
    applyIllum(mtl, where, m);
    conserveEnergy(m, where);

    // A texture statement's file, decoded once per encoding; errors name the statement's line.
    auto texture = [&](const std::string& texname, const std::string& statement,
                       TextureEncoding encoding) {
        const std::string name = slashes(texname);
        const std::string path = resolveRelative(mtlPath, name);
        try {
            assets.files().checkPath(path);
        } catch (const SceneError& e) {
            throw SceneError::atLine(mtlPath, mtlLine(mtlText, mtl.name, statement), e.message());
        }
        std::optional<int> index;
        try {
            index = assets.textureFile(path, encoding);
        } catch (const SceneError& e) {
            // A texture that exists but does not decode: say which statement wanted it.
            throw SceneError::atLine(mtlPath, mtlLine(mtlText, mtl.name, statement), e.what());
        }
        if (!index) {
            throw SceneError::atLine(
                mtlPath, mtlLine(mtlText, mtl.name, statement),
                "texture '" + name + "' not found (looked for '" + path + "')");
        }
        return *index;
    };
    if (!mtl.diffuse_texname.empty())
        m.diffuseTexture = texture(mtl.diffuse_texname, "map_Kd", TextureEncoding::Colour);

    // Opacity: d (or 1 - Tr) and map_d (the image's alpha, or its grey without one) are
    // stochastic coverage, as glTF's BLEND. Glass ignores d: exporters write d < 1 for what
    // is meant to refract, and glass transmits already.
    const float d = std::isfinite(mtl.dissolve) ? static_cast<float>(mtl.dissolve) : 1.0f;
    if (!m.glass) m.alpha = std::clamp(d, 0.0f, 1.0f);
    if (!mtl.alpha_texname.empty())
        m.alphaTexture = texture(mtl.alpha_texname, "map_d", TextureEncoding::Coverage);
    if (m.alpha < 1.0f || m.alphaTexture >= 0) m.alphaMode = AlphaMode::Blend;
    if (m.alpha <= 0.0f)
        spdlog::warn("{}: d 0 (or Tr 1) makes the material invisible: rays pass through it", where);

    // map_Ke: an emissive texture, per texel as glTF's emissiveTexture (the client's
    // EmissiveTexture.h). It multiplies Ke; a material that names the texture but says no Ke
    // emits the texture itself (Ke 1), since the texture would otherwise mean nothing. Ke
    // written out as black keeps the material dark, as a glTF emissiveFactor of zero does.
    if (!mtl.emissive_texname.empty()) {
        const bool saysKe =
            mtlLine(mtlText, mtl.name, "Ke") != mtlLine(mtlText, mtl.name, "newmtl");
        if (!saysKe && !m.isEmissive()) m.emission = glm::vec3(1.0f);
        if (m.isEmissive()) {
            m.emissionTexture = texture(mtl.emissive_texname, "map_Ke", TextureEncoding::Colour);
        } else {
            spdlog::warn("{}: map_Ke '{}' under Ke 0 emits nothing (Ke multiplies the texture)",
                         where, mtl.emissive_texname);
        }
    }

    // norm: a tangent-space normal map (green toward +v, -bm scaling its tilt), as glTF's
    // normalTexture; a bump map in the same material is then not used (one shading normal).
    if (!mtl.normal_texname.empty()) {
        m.normalTexture = texture(mtl.normal_texname, "norm", TextureEncoding::Data);
        const float bm = static_cast<float>(mtl.normal_texopt.bump_multiplier);
        m.normalScale = std::isfinite(bm) ? bm : 1.0f;
        if (!mtl.bump_texname.empty())
            spdlog::warn(
                "{}: both norm and bump / map_bump: the normal map '{}' is used, the bump "
                "map '{}' is not",
                where, mtl.normal_texname, mtl.bump_texname);
    }

    // bump / map_bump (-bm its scale): a height map, or a normal map where it reads as one.
    if (!mtl.bump_texname.empty() && mtl.normal_texname.empty()) {
        const int index =
            texture(mtl.bump_texname, bumpStatement(mtlText, mtl.name), TextureEncoding::Data);
        const float bm = static_cast<float>(mtl.bump_texopt.bump_multiplier);
        const float scale = std::isfinite(bm) ? bm : 1.0f;
        if (readsAsNormalMap(assets.scene().textures[index])) {
            spdlog::warn(
                "{}: bump map '{}' is RGB with its blue mostly above one half: read as a "
                "tangent-space normal map (green toward +v, -bm scaling its tilt), not as heights",
                where, mtl.bump_texname);
            m.normalTexture = index;
            m.normalScale = scale;
        } else {
            m.bumpTexture = index;
            m.bumpScale = scale;
        }
    }
    return m;
}

std::vector<std::string> unmodelledMtlStatements(const tinyobj::material_t& mtl) {
    std::vector<std::string> out;
    if (mtl.dissolve < 1.0 && (mtl.illum == 4 || mtl.illum == 6 || mtl.illum == 7))
        out.push_back("d / Tr on glass (ignored: glass transmits by its Fresnel terms)");
    if (!mtl.displacement_texname.empty()) out.push_back("disp");
    if (!mtl.specular_texname.empty()) out.push_back("map_Ks");
    if (!mtl.specular_highlight_texname.empty()) out.push_back("map_Ns");
    return out;
}

}  // namespace igi
