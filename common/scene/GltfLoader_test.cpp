// glTF: the hand-written triangle.gltf (node transforms, materials, a punctual light).

#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "scene/SceneLoader.h"
#include "scene/TestScenes.h"
#include "scene/TextureLoader.h"

namespace igi {
namespace {

void expectNear(glm::vec3 a, glm::vec3 b, float eps = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

class GltfTriangle : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        scene_ = new Scene(loadSceneFile(test::testdataDir() / "gltf" / "scene.json"));
    }
    static void TearDownTestSuite() { delete scene_; }
    static Scene* scene_;
};
Scene* GltfTriangle::scene_ = nullptr;

TEST_F(GltfTriangle, NodeTransformsAreBakedAndUvsFlipped) {
    ASSERT_EQ(scene_->meshes.size(), 1u);
    const Mesh& m = scene_->meshes[0];
    EXPECT_EQ(m.name, "triangle");
    // Three primitives share one accessor set: 3 x 3 vertices, translated by the node.
    ASSERT_EQ(m.triangles.size(), 3u);
    ASSERT_EQ(m.positions.size(), 9u);
    expectNear(m.positions[m.triangles[0].y], {1, 0, -2});
    expectNear(m.normals[m.triangles[0].y], {0, 0, 1});
    // glTF's v = 0 is the top of the image, igi's the bottom.
    EXPECT_EQ(m.uvs[m.triangles[0].x], glm::vec2(0, 1));
    EXPECT_EQ(m.uvs[m.triangles[0].z], glm::vec2(0, 0));
    EXPECT_EQ(m.materialIds, (std::vector<std::uint32_t>{0, 1, 2}));
}

TEST_F(GltfTriangle, Materials) {
    const auto& mats = scene_->materials;
    ASSERT_EQ(mats.size(), 3u);
    EXPECT_EQ(mats[0].name, "chrome");
    // Metallic-roughness as the specification's GGX (roughness 0.05: alpha 0.0025, a lobe).
    EXPECT_EQ(mats[0].reflection, Reflection::Ggx);
    expectNear(mats[0].diffuse, {0.9f, 0.8f, 0.7f});  // the base colour
    EXPECT_FLOAT_EQ(mats[0].metallic, 1.0f);
    EXPECT_FLOAT_EQ(mats[0].roughness, 0.05f);
    EXPECT_FALSE(mats[0].isSpecular());
    EXPECT_EQ(mats[1].name, "water");
    EXPECT_TRUE(mats[1].glass);
    EXPECT_FLOAT_EQ(mats[1].ior, 1.33f);
    EXPECT_EQ(mats[2].name, "glow");
    expectNear(mats[2].emission, {4, 2, 1});  // emissiveFactor x emissiveStrength
    expectNear(mats[2].diffuse, {0.2f, 0.3f, 0.4f});
    EXPECT_EQ(mats[2].reflection, Reflection::Ggx);
    EXPECT_FLOAT_EQ(mats[2].metallic, 0.0f);
    EXPECT_FLOAT_EQ(mats[2].roughness, 1.0f);  // the specification's default
}

TEST_F(GltfTriangle, PunctualLightPlacedByNodesAndMeshTransform) {
    ASSERT_EQ(scene_->punctualLights.size(), 3u);
    const PunctualLight& l = scene_->punctualLights[0];
    EXPECT_EQ(l.name, "lamp");
    // Node (0,3,0) under a node scaled by 2, then the scene file's translate (10,0,0).
    expectNear(l.position, {10, 6, 0});
    // color x candela / 683 (Blender's Standard conversion), intensity = 40 pi.
    expectNear(l.intensity, glm::vec3(40, 20, 10) * (3.14159265f / 683.0f), 1e-5f);
    EXPECT_EQ(l.kind, LightKind::Point);
}

TEST_F(GltfTriangle, SpotAndDirectionalLightsShineDownTheirNodesMinusZ) {
    ASSERT_EQ(scene_->punctualLights.size(), 3u);
    const PunctualLight& spot = scene_->punctualLights[1];
    EXPECT_EQ(spot.name, "spot");
    EXPECT_EQ(spot.kind, LightKind::Spot);
    expectNear(spot.position, {11, 2, 3});  // the node's translation, then the entry's
    expectNear(spot.direction, {0, 0, -1});
    expectNear(spot.intensity, glm::vec3(1.0f), 1e-6f);  // 683 cd
    EXPECT_NEAR(spot.innerDeg, glm::degrees(0.2f), 1e-4f);
    EXPECT_NEAR(spot.outerDeg, glm::degrees(0.5f), 1e-4f);
    const PunctualLight& sun = scene_->punctualLights[2];
    EXPECT_EQ(sun.name, "sun");
    EXPECT_EQ(sun.kind, LightKind::Directional);
    expectNear(sun.direction, {0, -1, 0}, 1e-5f);  // -Z turned -90 degrees about X
    expectNear(sun.intensity, {2, 2, 1}, 1e-5f);   // 1366 lux x colour / 683
}

TEST(GltfLoader, MissingImageNamesIt) {
    const std::string gltf = R"({"asset": {"version": "2.0"},
        "images": [{"uri": "gone.png"}], "textures": [{"source": 0}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]})";
    const std::string what = test::sceneErrorOf([&] {
        test::parseInline(
            R"({"meshes": [{"file": "a/m.gltf"}], "camera": {"position": [0, 0, 1], "look_at": [0, 0, 0]}})",
            {{"a/m.gltf", gltf}});
    });
    EXPECT_NE(what.find("a/m.gltf: /images/0: image 'gone.png' not found or unreadable"),
              std::string::npos)
        << what;
}

// Issue 40: a missing .bin printed "cannot load glTF: File not found : X.bin" and a blank line.
TEST(GltfLoader, MissingBufferNamesItInTheFileMessageForm) {
    const std::string what = test::sceneErrorOf([] {
        test::parseInline(
            R"({"meshes": [{"file": "a/m.gltf"}], "camera": {"position": [0, 0, 1], "look_at": [0, 0, 0]}})",
            {{"a/m.gltf", R"({"asset": {"version": "2.0"},
                              "buffers": [{"uri": "gone.bin", "byteLength": 12}]})"}});
    });
    EXPECT_NE(what.find("a/m.gltf: buffer 'gone.bin' not found or unreadable"), std::string::npos)
        << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
}

TEST(GltfLoader, InvalidJsonIsAnErrorNamingTheFile) {
    const std::string what = test::sceneErrorOf([] {
        test::parseInline(R"({"meshes": [{"file": "m.gltf"}]})", {{"m.gltf", "{ not json"}});
    });
    EXPECT_NE(what.find("m.gltf: cannot load glTF"), std::string::npos) << what;
}

using test::plainGltfWith;

// A required extension that igi does not model is an error naming it; a used one, and every
// material feature rendered without, is named in one warning per file.
TEST(GltfFeatures, UnsupportedRequiredExtensionIsAnErrorAndUnmodelledOnesAreNamed) {
    const std::string error = test::sceneErrorOf([] {
        plainGltfWith([](nlohmann::json& g) {
            g["extensionsUsed"] = {"KHR_draco_mesh_compression", "KHR_materials_ior"};
            g["extensionsRequired"] = {"KHR_draco_mesh_compression", "KHR_materials_ior"};
        });
    });
    EXPECT_NE(error.find("plain.gltf"), std::string::npos) << error;
    EXPECT_NE(error.find("/extensionsRequired"), std::string::npos) << error;
    EXPECT_NE(error.find("requires KHR_draco_mesh_compression,"), std::string::npos) << error;

    test::CapturedLog log;
    plainGltfWith([](nlohmann::json& g) {
        g["extensionsUsed"] = {"KHR_materials_clearcoat", "KHR_materials_sheen",
                               "KHR_materials_emissive_strength"};
        g["materials"] = nlohmann::json::array(
            {{{"name", "a"}, {"occlusionTexture", {{"index", 0}}}, {"alphaMode", "MASK"}},
             {{"name", "b"}, {"occlusionTexture", {{"index", 0}}}}});
        g["textures"] = nlohmann::json::array({{{"source", 0}}});
        g["images"] = nlohmann::json::array({{{"uri", "missing.png"}}});
    });
    const std::string text = log.text();
    EXPECT_NE(text.find("plain.gltf: extensions not modelled, rendered without them: "
                        "KHR_materials_clearcoat, KHR_materials_sheen"),
              std::string::npos)
        << text;
    // alphaMode is modelled (client/tracing/AlphaCoverage.h): not named.
    EXPECT_EQ(text.find("alphaMode"), std::string::npos) << text;
    EXPECT_NE(text.find("occlusionTexture"), std::string::npos) << text;
    // One warning per file, not per material.
    EXPECT_NE(text.find("occlusionTexture"), std::string::npos) << text;
    EXPECT_EQ(text.find("occlusionTexture"), text.rfind("occlusionTexture")) << text;
}

// Partial transmission (a factor strictly between 0 and 1, or a transmissionTexture), rough
// transmission and a texCoord other than 0 are not modelled: the warning names each material and
// slot, and what was rendered instead; a transmission of exactly 0 or 1 and texCoord 0 are not
// named.
TEST(GltfFeatures, PartialTransmissionAndOtherTexCoordsNameTheirMaterials) {
    test::CapturedLog log;
    const std::string pgm = std::string("P5\n2 1\n255\n") + char(0) + char(255);
    plainGltfWith(
        [](nlohmann::json& g) {
            g["extensionsUsed"] = {"KHR_materials_transmission", "KHR_texture_transform"};
            auto transmission = [](double factor) {
                return nlohmann::json{
                    {"KHR_materials_transmission", {{"transmissionFactor", factor}}}};
            };
            g["materials"] = nlohmann::json::array(
                {{{"name", "frosted"}, {"extensions", transmission(0.3)}},
                 {{"name", "tinted"},
                  {"extensions",
                   {{"KHR_materials_transmission",
                     {{"transmissionFactor", 0.8}, {"transmissionTexture", {{"index", 0}}}}}}}},
                 {{"name", "clear"},
                  {"pbrMetallicRoughness", {{"roughnessFactor", 0.0}}},
                  {"extensions", transmission(1.0)}},
                 {{"name", "solid"}, {"extensions", transmission(0.0)}},
                 {{"name", "second"},
                  {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}, {"texCoord", 1}}}}},
                  {"normalTexture",
                   {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"texCoord", 1}}}}}}}},
                 {{"name", "first"},
                  {"pbrMetallicRoughness",
                   {{"baseColorTexture", {{"index", 0}, {"texCoord", 0}}}}}},
                 {{"extensions", transmission(0.4)}}});
            g["textures"] = nlohmann::json::array({{{"source", 0}}});
            g["images"] = nlohmann::json::array({{{"uri", "t.pgm"}}});
        },
        {{"t.pgm", pgm}});
    const std::string text = log.text();
    EXPECT_NE(text.find("plain.gltf: material features not modelled"), std::string::npos) << text;
    EXPECT_NE(text.find("partial KHR_materials_transmission, all or nothing instead ('frosted' "
                        "(factor 0.3: rendered opaque); 'tinted' (factor 0.8, "
                        "transmissionTexture not read: rendered as clear glass); "
                        "'plain#material6' (factor 0.4: rendered opaque))"),
              std::string::npos)
        << text;
    // A material without a name is named as the loader names it.
    EXPECT_NE(text.find("'plain#material6' (factor 0.4: rendered opaque)"), std::string::npos)
        << text;
    EXPECT_NE(text.find("texCoord other than 0, TEXCOORD_0 read instead ('second' "
                        "baseColorTexture (texCoord 1); 'second' normalTexture (texCoord 1))"),
              std::string::npos)
        << text;
    // A transmitting material's roughness (the specification's default is 1) is modelled
    // (rough glass): no warning names it.
    EXPECT_EQ(text.find("rough transmission"), std::string::npos) << text;
    EXPECT_EQ(text.find("'clear'"), std::string::npos) << text;
    EXPECT_EQ(text.find("'solid'"), std::string::npos) << text;
    EXPECT_EQ(text.find("'first'"), std::string::npos) << text;
}

// KHR_materials_transmission with a roughness at or above the mirror threshold is rough glass
// (glass with a GGX interface, its ior from KHR_materials_ior); below it, smooth glass.
TEST(GltfFeatures, RoughTransmissionIsRoughGlass) {
    const Scene scene = plainGltfWith([](nlohmann::json& g) {
        auto glass = [](const char* name, double roughness) {
            return nlohmann::json{{"name", name},
                                  {"pbrMetallicRoughness", {{"roughnessFactor", roughness}}},
                                  {"extensions",
                                   {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                                    {"KHR_materials_ior", {{"ior", 1.33}}}}}};
        };
        g["materials"] = nlohmann::json::array(
            {glass("frosted", 0.4),
             glass("clear", 0.03),
             {{"name", "bare"},
              {"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}}}}});
        g["meshes"][0]["primitives"][0]["material"] = 0;
    });
    ASSERT_EQ(scene.materials.size(), 3u);
    const Material& frosted = scene.materials[0];
    EXPECT_TRUE(frosted.glass);
    EXPECT_EQ(frosted.reflection, Reflection::Ggx);
    EXPECT_FLOAT_EQ(frosted.roughness, 0.4f);
    EXPECT_FLOAT_EQ(frosted.ior, 1.33f);
    EXPECT_TRUE(frosted.isSpecular());  // caustic photons are aimed at it, no VPL is stored
    const Material& clear = scene.materials[1];
    EXPECT_TRUE(clear.glass);
    EXPECT_EQ(clear.reflection, Reflection::None);  // smooth: exactly the glass of before
    // Without pbrMetallicRoughness the roughness is the specification's default, 1.
    EXPECT_EQ(scene.materials[2].reflection, Reflection::Ggx);
    EXPECT_FLOAT_EQ(scene.materials[2].roughness, 1.0f);
}

// The default material of the specification (no pbrMetallicRoughness): a rough white metal.
TEST(GltfFeatures, MaterialWithoutMetallicRoughnessIsARoughWhiteMetal) {
    const Scene scene = plainGltfWith([](nlohmann::json& g) {
        g["materials"] = nlohmann::json::array({{{"name", "bare"}}});
        g["meshes"][0]["primitives"][0]["material"] = 0;
    });
    ASSERT_EQ(scene.materials.size(), 1u);
    const Material& m = scene.materials[0];
    EXPECT_EQ(m.reflection, Reflection::Ggx);
    EXPECT_FLOAT_EQ(m.metallic, 1.0f);
    EXPECT_FLOAT_EQ(m.roughness, 1.0f);
    EXPECT_EQ(m.diffuse, glm::vec3(1.0f));
}

// A data texture (metallicRoughnessTexture) keeps its 8-bit values; a colour one is sRGB.
TEST(GltfFeatures, DataTexturesAreNotSrgbDecoded) {
    // A 1 x 1 grey PGM of value 128.
    const std::string pgm = std::string("P5\n1 1\n255\n") + char(128);
    const Texture data = decodeTexture("grey.pgm", pgm, {}, TextureEncoding::Data);
    const Texture colour = decodeTexture("grey.pgm", pgm, {}, TextureEncoding::Colour);
    EXPECT_NEAR(data.texel(0).x, 128.0f / 255.0f, 1e-6f);
    EXPECT_NEAR(colour.texel(0).x, 0.2158605f, 1e-4f);  // sRGB 128
    EXPECT_EQ(data.minimum, data.texel(0));
}

// Little-endian bytes of `values`, as a glTF buffer holds them.
template <typename T>
std::string bytesOf(const std::vector<T>& values) {
    return std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

// plain.gltf's triangle with COLOR_0 from colours.bin, an accessor of `type` and
// `componentType` (normalized unless told otherwise).
Scene gltfWithColours(const std::string& type, int componentType, const std::string& bytes,
                      bool normalized = true) {
    return plainGltfWith(
        [&](nlohmann::json& g) {
            g["buffers"].push_back({{"uri", "colours.bin"}, {"byteLength", bytes.size()}});
            g["bufferViews"].push_back(
                {{"buffer", 1}, {"byteOffset", 0}, {"byteLength", bytes.size()}});
            nlohmann::json accessor = {
                {"bufferView", 2}, {"componentType", componentType}, {"count", 3}, {"type", type}};
            if (componentType != 5126) accessor["normalized"] = normalized;
            g["accessors"].push_back(accessor);
            g["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = 2;
        },
        {{"colours.bin", bytes}});
}

// COLOR_0 (linear) in the three component types the specification allows, RGB or RGBA: the
// mesh keeps RGB per vertex, which multiplies the base colour where it is hit.
TEST(GltfColours, FloatByteAndShortRgbOrRgba) {
    const Scene f = gltfWithColours(
        "VEC3", 5126, bytesOf<float>({1.0f, 0.5f, 0.25f, 0.0f, 1.0f, 0.0f, 0.2f, 0.4f, 0.6f}));
    ASSERT_EQ(f.meshes[0].colors.size(), 3u);
    expectNear(f.meshes[0].colors[0], {1.0f, 0.5f, 0.25f});
    expectNear(f.meshes[0].colors[2], {0.2f, 0.4f, 0.6f});
    const Scene b = gltfWithColours(
        "VEC4", 5121, bytesOf<std::uint8_t>({255, 0, 51, 255, 0, 255, 0, 128, 102, 102, 102, 255}));
    ASSERT_EQ(b.meshes[0].colors.size(), 3u);
    expectNear(b.meshes[0].colors[0], {1.0f, 0.0f, 0.2f});
    expectNear(b.meshes[0].colors[1], {0.0f, 1.0f, 0.0f});  // the alpha is dropped
    expectNear(b.meshes[0].colors[2], {0.4f, 0.4f, 0.4f});
    const Scene u = gltfWithColours(
        "VEC3", 5123, bytesOf<std::uint16_t>({65535, 0, 0, 0, 32768, 0, 0, 0, 13107}));
    ASSERT_EQ(u.meshes[0].colors.size(), 3u);
    expectNear(u.meshes[0].colors[1], {0.0f, 32768.0f / 65535.0f, 0.0f});
    expectNear(u.meshes[0].colors[2], {0.0f, 0.0f, 0.2f});
    // Without COLOR_0, no colours: the base colour alone.
    EXPECT_TRUE(plainGltfWith([](nlohmann::json&) {}).meshes[0].colors.empty());
}

// An integer COLOR_0 that is not normalized, or a scalar one, is an error naming the accessor.
TEST(GltfColours, UnnormalizedOrScalarColoursAreErrorsNamingTheAccessor) {
    const std::string bytes = bytesOf<std::uint8_t>({255, 0, 0, 0, 255, 0, 0, 0, 255});
    const std::string unnormalized =
        test::sceneErrorOf([&] { gltfWithColours("VEC3", 5121, bytes, false); });
    EXPECT_NE(unnormalized.find("/accessors/2"), std::string::npos) << unnormalized;
    EXPECT_NE(unnormalized.find("normalized"), std::string::npos) << unnormalized;
    const std::string scalar = test::sceneErrorOf([&] {
        gltfWithColours("SCALAR", 5126, bytesOf<float>({1, 1, 1}));
    });
    EXPECT_NE(scalar.find("COLOR_0 must be a VEC3 or VEC4"), std::string::npos) << scalar;
    EXPECT_NE(scalar.find("plain.gltf"), std::string::npos) << scalar;
}

// An emissive texture is kept per texel (sRGB, with its slot's transform): emission is the
// factor times the strength alone, no longer the texture's mean; no warning names it.
TEST(GltfEmission, EmissiveTextureIsKeptPerTexel) {
    test::CapturedLog log;
    // A 2 x 1 grey PGM: black, then white.
    const std::string pgm = std::string("P5\n2 1\n255\n") + char(0) + char(255);
    const Scene scene = plainGltfWith(
        [](nlohmann::json& g) {
            g["extensionsUsed"] = {"KHR_materials_emissive_strength", "KHR_texture_transform"};
            g["materials"] = nlohmann::json::array(
                {{{"name", "screen"},
                  {"emissiveFactor", {1.0, 0.5, 0.25}},
                  {"emissiveTexture",
                   {{"index", 0},
                    {"extensions", {{"KHR_texture_transform", {{"offset", {0.5, 0}}}}}}}},
                  {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4}}}}}},
                 {{"name", "unlit"}, {"emissiveTexture", {{"index", 0}}}}});
            g["textures"] = nlohmann::json::array({{{"source", 0}}});
            g["images"] = nlohmann::json::array({{{"uri", "e.pgm"}}});
            g["meshes"][0]["primitives"][0]["material"] = 0;
        },
        {{"e.pgm", pgm}});
    ASSERT_EQ(scene.materials.size(), 2u);
    const Material& m = scene.materials[0];
    expectNear(m.emission, {4.0f, 2.0f, 1.0f});  // not times the mean (one half)
    ASSERT_GE(m.emissionTexture, 0);
    const Texture& t = scene.textures[m.emissionTexture];
    ASSERT_EQ(t.width, 2);
    EXPECT_EQ(t.texel(0), glm::vec3(0.0f));
    EXPECT_NEAR(t.texel(1).x, 1.0f, 1e-6f);
    EXPECT_TRUE(m.emissionUv.active);
    // Without an emissive factor (its default is black) the texture emits nothing.
    EXPECT_FALSE(scene.materials[1].isEmissive());
    EXPECT_EQ(scene.materials[1].emissionTexture, -1);
    EXPECT_EQ(log.text().find("emissiveTexture"), std::string::npos) << log.text();
}

}  // namespace
}  // namespace igi
