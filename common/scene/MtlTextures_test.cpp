// MTL map_Ke (an emissive texture, per texel as glTF's emissiveTexture) and norm (a
// tangent-space normal map, as glTF's normalTexture). What they render is tested beside the
// client's emissive textures and normal maps (client/lights/EmissiveTexture_test.cpp,
// client/materials/MtlTextures_test.cpp).

#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "scene/SceneLoader.h"
#include "scene/TestScenes.h"
#include "util/ExpectContains.h"

namespace igi {
namespace {

const char* kOneMesh =
    R"({"meshes": [{"file": "m.obj"}], "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]}})";

// An 8-bit binary PPM of `rgb` texels, row-major from the top.
std::string ppm(int width, int height, const std::vector<int>& rgb) {
    std::string s = "P6\n" + std::to_string(width) + " " + std::to_string(height) + "\n255\n";
    for (int v : rgb) s += char(v);
    return s;
}

Scene mtlScene(const std::string& body) {
    std::map<std::string, std::string> files;
    files["m.obj"] =
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
        "usemtl a\nf 1/1 2/2 3/3\n";
    files["m.mtl"] = "newmtl a\nKd 0.5 0.5 0.5\n" + body;
    files["e.ppm"] = ppm(2, 1, {255, 0, 0, 0, 0, 255});
    files["n.ppm"] = ppm(2, 1, {128, 128, 255, 218, 128, 218});
    return test::parseInline(kOneMesh, files);
}

TEST(MtlEmissiveTexture, MapKeMultipliesKePerTexel) {
    test::CapturedLog log;
    const Scene s = mtlScene("Ke 2 2 2\nmap_Ke e.ppm\n");
    const Material& m = s.materials.at(0);
    ASSERT_GE(m.emissionTexture, 0);
    EXPECT_EQ(m.emission, glm::vec3(2.0f));
    // Decoded as a colour (sRGB): pure red and pure blue stay 1 in their channel.
    const Texture& t = s.textures.at(std::size_t(m.emissionTexture));
    ASSERT_EQ(t.texelCount(), 2u);
    EXPECT_FLOAT_EQ(t.texel(0).x, 1.0f);
    EXPECT_FLOAT_EQ(t.texel(0).z, 0.0f);
    EXPECT_FLOAT_EQ(t.texel(1).z, 1.0f);
    EXPECT_EQ(log.text().find("not modelled"), std::string::npos) << log.text();
}

TEST(MtlEmissiveTexture, MapKeWithoutKeEmitsTheTexture) {
    const Material m = mtlScene("map_Ke e.ppm\n").materials.at(0);
    ASSERT_GE(m.emissionTexture, 0);
    EXPECT_EQ(m.emission, glm::vec3(1.0f));
}

TEST(MtlEmissiveTexture, MapKeUnderKeZeroEmitsNothingAndSaysSo) {
    test::CapturedLog log;
    const Material m = mtlScene("Ke 0 0 0\nmap_Ke e.ppm\n").materials.at(0);
    EXPECT_FALSE(m.isEmissive());
    EXPECT_EQ(m.emissionTexture, -1);
    EXPECT_CONTAINS(log.text(), "m.mtl: material 'a': map_Ke 'e.ppm' under Ke 0 emits nothing");
}

TEST(MtlEmissiveTexture, MissingMapKeNamesItsLine) {
    const std::string what = test::sceneErrorOf([] {
        std::map<std::string, std::string> files;
        files["m.obj"] = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n";
        files["m.mtl"] = "newmtl a\nKe 1 1 1\nmap_Ke gone.png\n";
        test::parseInline(kOneMesh, files);
    });
    EXPECT_CONTAINS(what, "m.mtl:3: texture 'gone.png' not found");
}

TEST(MtlNormalMap, NormIsATangentSpaceNormalMapWithItsMultiplier) {
    test::CapturedLog log;
    const Material m = mtlScene("norm -bm 0.5 n.ppm\n").materials.at(0);
    ASSERT_GE(m.normalTexture, 0);
    EXPECT_EQ(m.bumpTexture, -1);
    EXPECT_FLOAT_EQ(m.normalScale, 0.5f);
    EXPECT_TRUE(m.perturbsNormal());
    EXPECT_EQ(log.text().find("not modelled"), std::string::npos) << log.text();
    // Without -bm: scale 1; decoded as data (128 is 0.502, not the sRGB curve's 0.216).
    const Scene s = mtlScene("norm n.ppm\n");
    const Material& plain = s.materials.at(0);
    EXPECT_FLOAT_EQ(plain.normalScale, 1.0f);
    EXPECT_NEAR(s.textures.at(std::size_t(plain.normalTexture)).texel(0).x, 128.0f / 255.0f, 1e-6f);
}

TEST(MtlNormalMap, NormWinsOverABumpMapWithAWarning) {
    test::CapturedLog log;
    const Material m = mtlScene("norm n.ppm\nbump e.ppm\n").materials.at(0);
    ASSERT_GE(m.normalTexture, 0);
    EXPECT_EQ(m.bumpTexture, -1);
    EXPECT_CONTAINS(log.text(),
                    "m.mtl: material 'a': both norm and bump / map_bump: the normal "
                    "map 'n.ppm' is used, the bump map 'e.ppm' is not");
}

}  // namespace
}  // namespace igi
