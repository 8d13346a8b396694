#include <cmath>
#include <cstring>
#include <map>
#include <string>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "scene/Environment.h"
#include "scene/FileSource.h"
#include "scene/SceneError.h"
#include "scene/SceneLoader.h"

namespace igi {
namespace {

using Files = std::map<std::string, std::string>;

Scene parse(const std::string& environment, Files files = {}) {
    BundleFileSource source(std::move(files));
    return parseScene(R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
                          "environment": )" +
                          environment + "}",
                      "inline.json", source, SceneLimits{});
}

std::string errorOf(const std::string& environment, Files files = {}) {
    try {
        parse(environment, std::move(files));
    } catch (const SceneError& e) {
        return e.what();
    }
    return "(no error)";
}

// A float PFM image (bottom row first), which OpenImageIO reads: w x h texels of `value`,
// except `special` at texel (x, y) counted from the top.
std::string pfm(int w, int h, float value, int x = -1, int y = -1, float special = 0.0f) {
    std::string bytes = "PF\n" + std::to_string(w) + " " + std::to_string(h) + "\n-1.0\n";
    for (int row = h - 1; row >= 0; --row)
        for (int col = 0; col < w; ++col)
            for (int c = 0; c < 3; ++c) {
                const float v = (col == x && row == y) ? special : value;
                char b[4];
                std::memcpy(b, &v, 4);
                bytes.append(b, 4);
            }
    return bytes;
}

TEST(EnvironmentJson, ConstantSky) {
    const Scene s = parse(R"({"radiance": [1, 2, 3]})");
    EXPECT_TRUE(s.environment.present());
    EXPECT_EQ(s.environment.radiance, glm::vec3(1, 2, 3));
    EXPECT_EQ(s.environment.texture, -1);
}

TEST(EnvironmentJson, MapWithScaleAndRotation) {
    const Scene s = parse(R"({"file": "sky.pfm", "scale": 2, "rotate_deg": 90})",
                          {{"sky.pfm", pfm(4, 2, 0.5f, 1, 0, 8.0f)}});
    ASSERT_GE(s.environment.texture, 0);
    const Texture& t = s.textures[std::size_t(s.environment.texture)];
    EXPECT_EQ(t.width, 4);
    EXPECT_EQ(t.height, 2);
    EXPECT_FLOAT_EQ(t.texel(1).x, 8.0f);  // row 0 is the top
    EXPECT_EQ(s.environment.radiance, glm::vec3(2));
    EXPECT_FLOAT_EQ(s.environment.rotateDeg, 90.0f);
}

TEST(EnvironmentJson, BadInputNamesTheFileTheKeyAndTheTexel) {
    EXPECT_NE(
        errorOf(R"({"file": "gone.exr"})").find("/environment/file: file 'gone.exr' not found"),
        std::string::npos)
        << errorOf(R"({"file": "gone.exr"})");
    const std::string notImage = errorOf(R"({"file": "sky.hdr"})", {{"sky.hdr", "not an image"}});
    EXPECT_NE(notImage.find("/environment/file: 'sky.hdr'"), std::string::npos) << notImage;
    const std::string nan =
        errorOf(R"({"file": "sky.pfm"})", {{"sky.pfm", pfm(4, 2, 1.0f, 2, 1, NAN)}});
    EXPECT_NE(nan.find("'sky.pfm': texel (2, 1) is nan"), std::string::npos) << nan;
    const std::string both =
        errorOf(R"({"file": "sky.pfm", "radiance": 1})", {{"sky.pfm", pfm(4, 2, 1.0f)}});
    EXPECT_NE(both.find("/environment/radiance: unknown key"), std::string::npos) << both;
    EXPECT_NE(errorOf(R"({"radiance": -1})").find("/environment/radiance"), std::string::npos);
}

TEST(EnvironmentMapping, BlendersOrientation) {
    // The image's centre looks along +X, +Z is at u = 0.75, the top row straight up.
    const glm::vec2 x = equirectUv({1, 0, 0}), z = equirectUv({0, 0, 1}),
                    up = equirectUv({0, 1, 0});
    EXPECT_NEAR(x.x, 0.5f, 1e-6f);
    EXPECT_NEAR(x.y, 0.5f, 1e-6f);
    EXPECT_NEAR(z.x, 0.75f, 1e-6f);
    EXPECT_NEAR(up.y, 0.0f, 1e-6f);
    EXPECT_NEAR(equirectUv({0, 0, -1}).x, 0.25f, 1e-6f);
    for (const glm::vec3 d : {glm::vec3(0.3f, -0.5f, 0.81f), glm::vec3(-0.7f, 0.1f, -0.7f)}) {
        const glm::vec3 n = glm::normalize(d);
        const glm::vec3 back = equirectDirection(equirectUv(n));
        EXPECT_NEAR(glm::length(back - n), 0.0f, 1e-5f);
    }
    // Turning right-handed about +Y by 90 degrees takes +X to -Z.
    const glm::vec3 t = turnAboutUp({1, 0, 0}, 90.0f);
    EXPECT_NEAR(t.z, -1.0f, 1e-6f);
    EXPECT_NEAR(t.x, 0.0f, 1e-6f);
}

}  // namespace
}  // namespace igi
