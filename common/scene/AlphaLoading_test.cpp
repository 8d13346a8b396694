// Alpha as the loaders read it: the alpha channel of textures (not premultiplied into the
// colours), coverage maps, MTL d / Tr / map_d and glTF alphaMode, alphaCutoff and
// baseColorFactor's alpha. The client's cut-outs are tested in client/tracing/Alpha_test.cpp.

#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "scene/SceneChange.h"
#include "scene/SceneLoader.h"
#include "scene/SceneState.h"
#include "scene/TestScenes.h"
#include "scene/TextureLoader.h"
#include "util/ExpectContains.h"
#include "util/TestPaths.h"

namespace igi {
namespace {

// A PNG of `channels` 8-bit channels, row-major from the top, encoded by OpenImageIO.
std::string pngBytes(int width, int height, int channels, const std::vector<unsigned char>& px) {
    const auto path = testing::scratchPath("alpha.png");
    auto out = OIIO::ImageOutput::create(path.string());
    EXPECT_TRUE(out);
    if (!out) return "";
    OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
    if (channels == 4) spec.alpha_channel = 3;
    if (channels == 2) spec.alpha_channel = 1;
    // The bytes as given: not divided by alpha on the way out.
    spec.attribute("oiio:UnassociatedAlpha", 1);
    EXPECT_TRUE(out->open(path.string(), spec));
    EXPECT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, px.data()));
    out->close();
    std::ifstream in(path, std::ios::binary);
    std::stringstream bytes;
    bytes << in.rdbuf();
    std::filesystem::remove(path);
    return bytes.str();
}

// 2 x 1 RGBA: opaque red, then a white texel of alpha 0.
std::string redAndClearWhite() {
    return pngBytes(2, 1, 4, {255, 0, 0, 255, 255, 255, 255, 0});
}

TEST(AlphaDecode, AlphaChannelIsKeptAndColoursAreNotPremultiplied) {
    const Texture t = decodeTexture("a.png", redAndClearWhite());
    ASSERT_EQ(t.alpha.size(), 2u);
    EXPECT_FLOAT_EQ(t.alpha[0], 1.0f);
    EXPECT_FLOAT_EQ(t.alpha[1], 0.0f);
    EXPECT_FLOAT_EQ(t.alphaMinimum, 0.0f);
    // Premultiplied, the clear texel would be black.
    EXPECT_EQ(t.texel(1), glm::vec3(1.0f));
    EXPECT_EQ(t.texel(0), glm::vec3(1, 0, 0));
    // Bilinear: halfway between the texel centres, half covered.
    EXPECT_NEAR(t.sampleAlpha({0.5f, 0.5f}), 0.5f, 1e-6f);
    EXPECT_NEAR(t.sampleAlpha({0.25f, 0.5f}), 1.0f, 1e-6f);
    // The same as data (no sRGB curve on colours; alpha is never curved).
    const Texture d = decodeTexture("a.png", redAndClearWhite(), {}, TextureEncoding::Data);
    EXPECT_EQ(d.alpha, t.alpha);
}

TEST(AlphaDecode, GreyAlphaAndOpaqueImages) {
    // Grey + alpha: 2 channels, the second is alpha (128 = 0.502, linear).
    const Texture ga = decodeTexture("ga.png", pngBytes(1, 1, 2, {255, 128}));
    ASSERT_EQ(ga.alpha.size(), 1u);
    EXPECT_NEAR(ga.alpha[0], 128.0f / 255.0f, 1e-6f);
    EXPECT_EQ(ga.texel(0), glm::vec3(1.0f));
    // An RGBA image whose alpha is one everywhere, and an RGB one: no alpha kept.
    const Texture full = decodeTexture("f.png", pngBytes(1, 1, 4, {10, 20, 30, 255}));
    EXPECT_TRUE(full.alpha.empty());
    EXPECT_FLOAT_EQ(full.alphaMinimum, 1.0f);
    EXPECT_FLOAT_EQ(full.sampleAlpha({0.3f, 0.3f}), 1.0f);
    const Texture rgb = decodeTexture("c.png", pngBytes(1, 1, 3, {10, 20, 30}));
    EXPECT_TRUE(rgb.alpha.empty());
    EXPECT_EQ(rgb.texel(0), full.texel(0));
}

TEST(AlphaDecode, CoverageMapWithoutAlphaIsItsGrey) {
    const std::string grey = pngBytes(2, 1, 1, {128, 255});
    const Texture c = decodeTexture("g.png", grey, {}, TextureEncoding::Coverage);
    ASSERT_EQ(c.alpha.size(), 2u);
    EXPECT_NEAR(c.alpha[0], 128.0f / 255.0f, 1e-6f);  // linear, not sRGB-decoded
    EXPECT_FLOAT_EQ(c.alpha[1], 1.0f);
    EXPECT_TRUE(decodeTexture("g.png", grey).alpha.empty());  // as a colour: no alpha
    // With an alpha channel, that channel.
    const Texture a = decodeTexture("a.png", redAndClearWhite(), {}, TextureEncoding::Coverage);
    EXPECT_FLOAT_EQ(a.alpha[0], 1.0f);
    EXPECT_FLOAT_EQ(a.alpha[1], 0.0f);
}

// ---- MTL

const char* kOneMesh =
    R"({"meshes": [{"file": "m.obj"}], "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]}})";

Material mtlMaterial(const std::string& body, std::map<std::string, std::string> files = {}) {
    files["m.obj"] =
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
        "usemtl a\nf 1/1 2/2 3/3\n";
    files["m.mtl"] = "newmtl a\nKd 0.5 0.5 0.5\n" + body;
    const Scene s = test::parseInline(kOneMesh, files);
    EXPECT_EQ(s.materials.size(), 1u);
    Material m = s.materials.at(0);
    if (m.alphaTexture >= 0) {
        EXPECT_LT(m.alphaTexture, static_cast<int>(s.textures.size()));
        m.name = std::to_string(s.textures[m.alphaTexture].alpha.size()) + " " +
                 std::to_string(s.textures[m.alphaTexture].alphaMinimum);
    }
    return m;
}

TEST(AlphaMtl, DissolveAndTransparencyAreBlendCoverage) {
    const Material d = mtlMaterial("d 0.25\n");
    EXPECT_EQ(d.alphaMode, AlphaMode::Blend);
    EXPECT_FLOAT_EQ(d.alpha, 0.25f);
    EXPECT_EQ(d.alphaTexture, -1);
    const Material tr = mtlMaterial("Tr 0.75\n");
    EXPECT_EQ(tr.alphaMode, AlphaMode::Blend);
    EXPECT_FLOAT_EQ(tr.alpha, 0.25f);
    const Material opaque = mtlMaterial("d 1\n");
    EXPECT_EQ(opaque.alphaMode, AlphaMode::Opaque);
    EXPECT_FLOAT_EQ(opaque.alpha, 1.0f);
    EXPECT_EQ(mtlMaterial("").alphaMode, AlphaMode::Opaque);
    // Glass ignores d, and says so.
    test::CapturedLog log;
    const Material glass = mtlMaterial("illum 7\nNi 1.5\nd 0.5\n");
    EXPECT_TRUE(glass.glass);
    EXPECT_EQ(glass.alphaMode, AlphaMode::Opaque);
    EXPECT_CONTAINS(log.text(), "d / Tr on glass");
}

TEST(AlphaMtl, MapDIsTheImagesAlphaOrItsGrey) {
    const Material grey =
        mtlMaterial("map_d mask.png\n", {{"mask.png", pngBytes(2, 1, 1, {0, 255})}});
    EXPECT_EQ(grey.alphaMode, AlphaMode::Blend);
    EXPECT_FLOAT_EQ(grey.alpha, 1.0f);
    ASSERT_GE(grey.alphaTexture, 0);
    EXPECT_EQ(grey.name, "2 0.000000");  // two alpha values, the least 0
    const Material rgba =
        mtlMaterial("map_Kd leaf.png\nmap_d leaf.png\n", {{"leaf.png", redAndClearWhite()}});
    EXPECT_EQ(rgba.alphaMode, AlphaMode::Blend);
    ASSERT_GE(rgba.alphaTexture, 0);
    EXPECT_EQ(rgba.name, "2 0.000000");
    EXPECT_NE(rgba.alphaTexture, rgba.diffuseTexture);  // decoded as coverage, once more
    // A missing map_d names its line.
    const std::string what = test::sceneErrorOf([] { mtlMaterial("map_d gone.png\n"); });
    EXPECT_CONTAINS(what, "m.mtl:3: texture 'gone.png' not found");
}

TEST(AlphaOverrides, SceneFileSetsModeFactorAndCutoff) {
    const Scene s = test::parseInline(
        R"({"meshes": [{"file": "m.obj"}], "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
            "materials": {"a": {"alpha_mode": "mask", "alpha": 0.8, "alpha_cutoff": 0.3}}})",
        {{"m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n"},
         {"m.mtl", "newmtl a\nKd 0.5 0.5 0.5\n"}});
    const Material& m = s.materials.at(0);
    EXPECT_EQ(m.alphaMode, AlphaMode::Mask);
    EXPECT_FLOAT_EQ(m.alpha, 0.8f);
    EXPECT_FLOAT_EQ(m.alphaCutoff, 0.3f);
    const std::string what = test::sceneErrorOf([] {
        test::parseInline(
            R"({"meshes": [{"file": "m.obj"}], "materials": {"a": {"alpha_mode": "clip"}}})",
            {{"m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n"},
             {"m.mtl", "newmtl a\n"}});
    });
    EXPECT_CONTAINS(what, "alpha_mode");
}

// A live material change carries no coverage (and no uv transform): the receiver keeps its own.
TEST(AlphaLive, MaterialChangesKeepCoverageAndUvTransforms) {
    SceneState state;
    Material m;
    m.alphaMode = AlphaMode::Mask;
    m.alpha = 0.7f;
    m.alphaCutoff = 0.3f;
    m.alphaTexture = 2;
    m.diffuseUv.active = true;
    m.diffuseUv.offset = {0.5f, 0.0f};
    state.materials = {m};
    Material changed;  // as decoded from the wire: defaults but for what the change carries
    changed.diffuse = glm::vec3(0.2f);
    applyChanges(state, {MaterialChange{0, changed}});
    const Material& after = state.materials[0];
    EXPECT_EQ(after.diffuse, glm::vec3(0.2f));
    EXPECT_EQ(after.alphaMode, AlphaMode::Mask);
    EXPECT_FLOAT_EQ(after.alpha, 0.7f);
    EXPECT_FLOAT_EQ(after.alphaCutoff, 0.3f);
    EXPECT_EQ(after.alphaTexture, 2);
    EXPECT_EQ(after.diffuseUv, m.diffuseUv);
}

// ---- glTF

using test::plainGltfWith;

TEST(AlphaGltf, AlphaModeCutoffAndFactor) {
    test::CapturedLog log;
    const Scene scene = plainGltfWith(
        [](nlohmann::json& g) {
            g["materials"] = nlohmann::json::array(
                {{{"name", "mask"},
                  {"alphaMode", "MASK"},
                  {"alphaCutoff", 0.3},
                  {"pbrMetallicRoughness",
                   {{"baseColorFactor", {1, 1, 1, 0.6}}, {"baseColorTexture", {{"index", 0}}}}}},
                 {{"name", "blend"},
                  {"alphaMode", "BLEND"},
                  {"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 0.4}}}}},
                 {{"name", "opaque"},
                  {"pbrMetallicRoughness",
                   {{"baseColorFactor", {1, 1, 1, 0.2}}, {"baseColorTexture", {{"index", 0}}}}}},
                 {{"name", "default cut-off"}, {"alphaMode", "MASK"}}});
            g["textures"] = nlohmann::json::array({{{"source", 0}}});
            g["images"] = nlohmann::json::array({{{"uri", "a.png"}}});
            g["meshes"][0]["primitives"][0]["material"] = 0;
        },
        {{"a.png", redAndClearWhite()}});
    ASSERT_EQ(scene.materials.size(), 4u);
    const Material& mask = scene.materials[0];
    EXPECT_EQ(mask.alphaMode, AlphaMode::Mask);
    EXPECT_FLOAT_EQ(mask.alphaCutoff, 0.3f);
    EXPECT_FLOAT_EQ(mask.alpha, 0.6f);
    ASSERT_GE(mask.alphaTexture, 0);
    EXPECT_EQ(mask.alphaTexture, mask.diffuseTexture);  // the base colour texture's alpha
    EXPECT_EQ(scene.textures[mask.alphaTexture].alpha.size(), 2u);
    const Material& blend = scene.materials[1];
    EXPECT_EQ(blend.alphaMode, AlphaMode::Blend);
    EXPECT_FLOAT_EQ(blend.alpha, 0.4f);
    EXPECT_EQ(blend.alphaTexture, -1);
    // OPAQUE ignores the factor's alpha and the texture's.
    const Material& opaque = scene.materials[2];
    EXPECT_EQ(opaque.alphaMode, AlphaMode::Opaque);
    EXPECT_FLOAT_EQ(opaque.alpha, 1.0f);
    EXPECT_EQ(opaque.alphaTexture, -1);
    EXPECT_FLOAT_EQ(scene.materials[3].alphaCutoff, 0.5f);  // the specification's default
    EXPECT_EQ(log.text().find("alphaMode"), std::string::npos) << log.text();
}

}  // namespace
}  // namespace igi
