// glTF KHR_texture_transform: offset, rotation and scale of every texture slot, mapped to
// igi's uvs (v up the image, glTF's down); texCoord (the extension's or the slot's) other than
// 0 is still named in the warning.

#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "scene/SceneLoader.h"
#include "scene/TestScenes.h"

namespace igi {
namespace {

// A 1 x 1 PGM as every texture: only the materials are looked at.
Scene plainGltfWith(const std::function<void(nlohmann::json&)>& edit) {
    return test::plainGltfWith(edit, {{"t.pgm", std::string("P5\n1 1\n255\n") + char(128)}});
}

// glTF's uv (u, v down) of igi's (u, v up).
glm::vec2 gltfUv(glm::vec2 igi) {
    return {igi.x, 1.0f - igi.y};
}

void expectNear(glm::vec2 a, glm::vec2 b) {
    EXPECT_NEAR(a.x, b.x, 1e-5f);
    EXPECT_NEAR(a.y, b.y, 1e-5f);
}

nlohmann::json slot(const nlohmann::json& transform) {
    return {{"index", 0}, {"extensions", {{"KHR_texture_transform", transform}}}};
}

TEST(TextureTransform, EverySlotIsReadInIgisUvs) {
    test::CapturedLog log;
    const Scene scene = plainGltfWith([](nlohmann::json& g) {
        g["extensionsUsed"] = {"KHR_texture_transform"};
        g["extensionsRequired"] = {"KHR_texture_transform"};  // supported: no error
        g["materials"] = nlohmann::json::array(
            {{{"name", "all"},
              {"alphaMode", "MASK"},
              {"pbrMetallicRoughness",
               {{"baseColorTexture", slot({{"offset", {0.5, 0.0}}})},
                {"metallicRoughnessTexture", slot({{"scale", {2.0, 3.0}}})}}},
              {"normalTexture", slot({{"rotation", 1.5707963267948966}})}},
             {{"name", "spec example"},
              {"pbrMetallicRoughness",
               {{"baseColorTexture",
                 slot({{"offset", {0, 1}}, {"rotation", 1.57079632679}, {"scale", {0.5, 0.5}}})}}}},
             {{"name", "plain"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}},
             {{"name", "texCoord"},
              {"pbrMetallicRoughness", {{"baseColorTexture", slot({{"texCoord", 1}})}}}}});
        g["textures"] = nlohmann::json::array({{{"source", 0}}});
        g["images"] = nlohmann::json::array({{{"uri", "t.pgm"}}});
    });
    ASSERT_GE(scene.materials.size(), 4u);  // and the default one of the material-less primitive
    const Material& all = scene.materials[0];
    // Offset (0.5, 0): u moves by a half, v stays.
    ASSERT_TRUE(all.diffuseUv.active);
    expectNear(all.diffuseUv({0.1f, 0.2f}), {0.6f, 0.2f});
    EXPECT_EQ(all.alphaUv, all.diffuseUv);  // alpha is the base colour texture's
    // Scale (2, 3) about glTF's origin, the top left: igi's v = 1 - 3 (1 - v).
    expectNear(all.metallicRoughnessUv({0.1f, 0.8f}), {0.2f, 1.0f - 3.0f * 0.2f});
    // Rotation by 90 degrees: glTF (u, v) -> (v, -u).
    const glm::vec2 g = gltfUv({0.3f, 0.9f});
    expectNear(all.normalUv({0.3f, 0.9f}), gltfUv({g.y, -g.x}));
    // The specification's example: "the lower left quadrant of the image, rotated clockwise
    // 90 degrees": glTF's corners (0, 0), (1, 0), (1, 1), (0, 1) go to (0, 1), (0, 0.5),
    // (0.5, 0.5), (0.5, 1).
    const UvTransform& example = scene.materials[1].diffuseUv;
    expectNear(example(gltfUv({0, 0})), gltfUv({0, 1}));
    expectNear(example(gltfUv({1, 0})), gltfUv({0, 0.5f}));
    expectNear(example(gltfUv({1, 1})), gltfUv({0.5f, 0.5f}));
    expectNear(example(gltfUv({0, 1})), gltfUv({0.5f, 1}));
    // No extension: inactive, the uv itself (bit for bit).
    EXPECT_FALSE(scene.materials[2].diffuseUv.active);
    EXPECT_EQ(scene.materials[2].diffuseUv({0.1234f, 5.678f}), glm::vec2(0.1234f, 5.678f));
    // The transform is no longer named; the extension's texCoord 1 is.
    const std::string text = log.text();
    EXPECT_EQ(text.find("KHR_texture_transform"), std::string::npos) << text;
    EXPECT_NE(text.find("texCoord other than 0"), std::string::npos) << text;
}

}  // namespace
}  // namespace igi

namespace igi {
namespace {

// A texture's sampler sets how its lookups continue past the edges (REPEAT without one); a
// value that is no wrap mode is an error naming the sampler's field; NEAREST filters are named
// in the warning (lookups are bilinear).
TEST(GltfSamplers, WrapModesAreReadAndNearestFiltersWarned) {
    test::CapturedLog log;
    const Scene scene = plainGltfWith([](nlohmann::json& g) {
        g["materials"] = nlohmann::json::array(
            {{{"name", "clamped"},
              {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}},
             {{"name", "mirrored"},
              {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 1}}}}}},
             {{"name", "plain"},
              {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 2}}}}}}});
        g["samplers"] =
            nlohmann::json::array({{{"wrapS", 33071}, {"wrapT", 33071}, {"magFilter", 9728}},
                                   {{"wrapS", 33648}, {"wrapT", 10497}}});
        g["textures"] = nlohmann::json::array(
            {{{"source", 0}, {"sampler", 0}}, {{"source", 0}, {"sampler", 1}}, {{"source", 0}}});
        g["images"] = nlohmann::json::array({{{"uri", "t.pgm"}}});
    });
    auto textureOf = [&](const std::string& name) -> const Texture& {
        for (const Material& m : scene.materials)
            if (m.name == name) return scene.textures.at(std::size_t(m.diffuseTexture));
        throw std::runtime_error("no material " + name);
    };
    EXPECT_EQ(textureOf("clamped").wrapU, TextureWrap::ClampToEdge);
    EXPECT_EQ(textureOf("clamped").wrapV, TextureWrap::ClampToEdge);
    EXPECT_EQ(textureOf("mirrored").wrapU, TextureWrap::MirroredRepeat);
    EXPECT_EQ(textureOf("mirrored").wrapV, TextureWrap::Repeat);
    EXPECT_EQ(textureOf("plain").wrapU, TextureWrap::Repeat);
    EXPECT_EQ(textureOf("plain").wrapV, TextureWrap::Repeat);
    EXPECT_EQ(scene.textures.size(), 3u) << "one image, three samplers: three textures";
    EXPECT_NE(log.text().find("NEAREST texture filters, bilinear instead (sampler 0)"),
              std::string::npos)
        << log.text();

    try {
        plainGltfWith([](nlohmann::json& g) {
            g["materials"] = nlohmann::json::array(
                {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
            g["samplers"] = nlohmann::json::array({{{"wrapS", 1234}}});
            g["textures"] = nlohmann::json::array({{{"source", 0}, {"sampler", 0}}});
            g["images"] = nlohmann::json::array({{{"uri", "t.pgm"}}});
        });
        FAIL() << "a wrap mode of 1234 was accepted";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("/samplers/0/wrapS"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("1234 is not a wrap mode"), std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace igi
