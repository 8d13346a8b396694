// MTL bump maps: a height map stays one (bumpTexture, -bm its scale); an RGB map whose blue is
// mostly above one half and whose texels are unit vectors is read as a normal map, with a
// warning that says so. The shading they give is tested in client/materials/BumpMap_test.cpp.

#include "scene/BumpMapKind.h"

#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "scene/SceneLoader.h"
#include "scene/TestScenes.h"
#include "util/ExpectContains.h"

namespace igi {
namespace {

// An 8-bit binary PPM of `rgb` texels, row-major from the top.
std::string ppm(int width, int height, const std::vector<int>& rgb) {
    std::string s = "P6\n" + std::to_string(width) + " " + std::to_string(height) + "\n255\n";
    for (int v : rgb) s += char(v);
    return s;
}

Texture texelsOf(const std::vector<glm::vec3>& texels) {
    Texture t;
    t.width = int(texels.size());
    t.height = 1;
    t.texels = texels;
    return t;
}

TEST(BumpMapKind, NormalMapsAreTheRgbUnitVectorsWithBlueAboveOneHalf) {
    // A flat normal map, and one tilted 30 degrees about v.
    EXPECT_TRUE(readsAsNormalMap(texelsOf({{0.5f, 0.5f, 1.0f}, {0.75f, 0.5f, 0.933f}})));
    // A grey height map, even a bright one, is heights.
    EXPECT_FALSE(readsAsNormalMap(texelsOf({{0.8f, 0.8f, 0.8f}, {0.9f, 0.9f, 0.9f}})));
    // A bright colour image (stone) has its blue above one half but is no unit vector.
    EXPECT_FALSE(readsAsNormalMap(texelsOf({{0.8f, 0.75f, 0.7f}, {0.7f, 0.68f, 0.6f}})));
    // A map whose blue is above one half in fewer than 90 % of its texels is heights.
    std::vector<glm::vec3> mostly(10, glm::vec3(0.5f, 0.5f, 1.0f));
    mostly[0] = mostly[1] = glm::vec3(0.5f, 0.5f, 0.2f);
    EXPECT_FALSE(readsAsNormalMap(texelsOf(mostly)));
    mostly[1] = glm::vec3(0.5f, 0.5f, 1.0f);
    EXPECT_TRUE(readsAsNormalMap(texelsOf(mostly)));
    EXPECT_FALSE(readsAsNormalMap(Texture{}));
}

const char* kOneMesh =
    R"({"meshes": [{"file": "m.obj"}], "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]}})";

Scene mtlScene(const std::string& body, const std::string& image) {
    std::map<std::string, std::string> files;
    files["m.obj"] =
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
        "usemtl a\nf 1/1 2/2 3/3\n";
    files["m.mtl"] = "newmtl a\nKd 0.5 0.5 0.5\n" + body;
    files["h.ppm"] = image;
    return test::parseInline(kOneMesh, files);
}

TEST(BumpMapMtl, HeightMapWithItsMultiplier) {
    test::CapturedLog log;
    const Scene s = mtlScene("bump -bm 2.5 h.ppm\n", ppm(2, 1, {0, 0, 0, 255, 255, 255}));
    const Material& m = s.materials.at(0);
    ASSERT_GE(m.bumpTexture, 0);
    EXPECT_FLOAT_EQ(m.bumpScale, 2.5f);
    EXPECT_EQ(m.normalTexture, -1);
    EXPECT_TRUE(m.perturbsNormal());
    // Decoded as data (heights, not colours): 255 is 1 and no sRGB curve bends 128.
    EXPECT_FLOAT_EQ(s.textures[m.bumpTexture].texel(1).x, 1.0f);
    // Modelled: no "not modelled" warning names it.
    EXPECT_EQ(log.text().find("bump"), std::string::npos) << log.text();
    // map_bump without -bm: scale 1.
    const Scene plain = mtlScene("map_bump h.ppm\n", ppm(2, 1, {0, 0, 0, 128, 128, 128}));
    EXPECT_FLOAT_EQ(plain.materials.at(0).bumpScale, 1.0f);
    EXPECT_GE(plain.materials.at(0).bumpTexture, 0);
}

TEST(BumpMapMtl, RgbNormalMapIsReadAsOneWithAWarning) {
    test::CapturedLog log;
    const Scene s = mtlScene("map_bump -bm 0.5 h.ppm\n", ppm(2, 1, {128, 128, 255, 160, 128, 250}));
    const Material& m = s.materials.at(0);
    EXPECT_EQ(m.bumpTexture, -1);
    ASSERT_GE(m.normalTexture, 0);
    EXPECT_FLOAT_EQ(m.normalScale, 0.5f);
    EXPECT_CONTAINS(log.text(),
                    "m.mtl: material 'a': bump map 'h.ppm' is RGB with its blue "
                    "mostly above one half: read as a tangent-space normal map");
}

TEST(BumpMapMtl, MissingBumpMapNamesItsLine) {
    const std::string what = test::sceneErrorOf([] {
        std::map<std::string, std::string> files;
        files["m.obj"] = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n";
        files["m.mtl"] = "newmtl a\nKd 0.5 0.5 0.5\nbump gone.png\n";
        test::parseInline(kOneMesh, files);
    });
    EXPECT_CONTAINS(what, "m.mtl:3: texture 'gone.png' not found");
}

}  // namespace
}  // namespace igi
