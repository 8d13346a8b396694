#include <map>

#include <spdlog/spdlog.h>

#include "scene/MtlMaterials.h"
#include "scene/SceneError.h"
#include "scene/SceneSections.h"

namespace igi {

void applyMaterialType(const JsonNode& node, Material& m) {
    const std::string type =
        node.choice({"diffuse", "glossy", "mirror", "glass", "rough_glass", "metallic_roughness"});
    // rough_glass: glass whose interface is a GGX BSDF of alpha = roughness^2 (Material.h).
    m.glass = type == "glass" || type == "rough_glass";
    m.reflection = type == "glossy"                                        ? Reflection::Glossy
                   : type == "mirror"                                      ? Reflection::Mirror
                   : type == "metallic_roughness" || type == "rough_glass" ? Reflection::Ggx
                                                                           : Reflection::None;
}

namespace {

void apply(const JsonNode& node, const std::optional<int>& texture, Material& m) {
    if (auto v = node.find("type")) applyMaterialType(*v, m);
    // Albedos and tints are fractions in [0, 1] per channel.
    if (auto v = node.find("diffuse")) m.diffuse = v->rgb(NumberRange::closed(0, 1));
    if (auto v = node.find("specular")) m.specular = v->rgb(NumberRange::closed(0, 1));
    if (auto v = node.find("phong_exponent")) m.phongExponent = v->real(NumberRange::atLeast(0));
    if (auto v = node.find("ior")) m.ior = v->real(NumberRange::above(0));
    if (auto v = node.find("transmittance")) m.transmittance = v->rgb(NumberRange::closed(0, 1));
    // Radiance emitted from the front (counter-clockwise) side.
    if (auto v = node.find("emission")) m.emission = v->rgb(NumberRange::atLeast(0));
    if (auto v = node.find("roughness")) m.roughness = v->real(NumberRange::closed(0, 1));
    if (auto v = node.find("metallic")) m.metallic = v->real(NumberRange::closed(0, 1));
    if (texture) m.diffuseTexture = *texture;
    // Coverage (docs/MATERIALS.md, "Alpha"): read when the scene loads, never changed live.
    if (auto v = node.find("alpha_mode")) {
        const std::string mode = v->choice({"opaque", "mask", "blend"});
        m.alphaMode = mode == "mask"    ? AlphaMode::Mask
                      : mode == "blend" ? AlphaMode::Blend
                                        : AlphaMode::Opaque;
    }
    if (auto v = node.find("alpha")) m.alpha = v->real(NumberRange::closed(0, 1));
    if (auto v = node.find("alpha_cutoff")) m.alphaCutoff = v->real(NumberRange::closed(0, 1));
}

std::optional<int> overrideTexture(const JsonNode& node, SceneAssets& assets) {
    auto v = node.find("texture");
    if (!v) return std::nullopt;
    const std::string written = v->string();
    // Relative to the scene file.
    const std::string path = resolveRelative("", written);
    try {
        assets.files().checkPath(path);
    } catch (const SceneError& e) {
        v->fail(e.message());
    }
    const std::optional<int> index = assets.textureFile(path);
    if (!index) v->fail("texture '" + written + "' not found");
    return index;
}

}  // namespace

void applyMaterialOverrides(const JsonNode& node, SceneAssets& assets) {
    // By name once: a scene file may override many names of a scene with many materials.
    std::multimap<std::string, std::size_t> byName;
    auto& materials = assets.scene().materials;
    for (std::size_t i = 0; i < materials.size(); ++i) byName.emplace(materials[i].name, i);
    for (const auto& [name, value] : node.members()) {
        value.checkKeys({"type", "diffuse", "specular", "phong_exponent", "ior", "transmittance",
                         "emission", "roughness", "metallic", "texture", "alpha_mode", "alpha",
                         "alpha_cutoff"});
        const auto [first, last] = byName.equal_range(name);
        if (first == last) value.fail("no loaded mesh has a material named '" + name + "'");
        const std::optional<int> texture = overrideTexture(value, assets);
        for (auto it = first; it != last; ++it) {
            Material& m = materials[it->second];
            apply(value, texture, m);
            conserveEnergy(m, value.file() + ": " + value.path());
        }
    }
}

}  // namespace igi
