#include "scene/Texture.h"

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "scene/FileSource.h"
#include "scene/TestScenes.h"
#include "scene/TextureLoader.h"
#include "util/TestPaths.h"

namespace igi {
namespace {

const glm::vec3 kA{1, 0, 0}, kB{0, 1, 0}, kC{0, 0, 1}, kD{1, 1, 1};

// Row 0 (top, v = 1): A B; row 1 (bottom, v = 0): C D.
Texture twoByTwo() {
    Texture t;
    t.width = 2;
    t.height = 2;
    t.texels = {kA, kB, kC, kD};
    return t;
}

void expectNear(glm::vec3 a, glm::vec3 b) {
    EXPECT_NEAR(a.x, b.x, 1e-5f);
    EXPECT_NEAR(a.y, b.y, 1e-5f);
    EXPECT_NEAR(a.z, b.z, 1e-5f);
}

TEST(TextureSample, TexelCentresAndOrientation) {
    const Texture t = twoByTwo();
    expectNear(t.sample({0.25f, 0.75f}), kA);  // top left
    expectNear(t.sample({0.75f, 0.75f}), kB);
    expectNear(t.sample({0.25f, 0.25f}), kC);  // v = 0 is the bottom row
    expectNear(t.sample({0.75f, 0.25f}), kD);
}

TEST(TextureSample, BilinearBetweenCentres) {
    const Texture t = twoByTwo();
    expectNear(t.sample({0.5f, 0.75f}), (kA + kB) * 0.5f);
    expectNear(t.sample({0.25f, 0.5f}), (kA + kC) * 0.5f);
    expectNear(t.sample({0.5f, 0.5f}), (kA + kB + kC + kD) * 0.25f);
    expectNear(t.sample({0.375f, 0.75f}), kA * 0.75f + kB * 0.25f);
}

TEST(TextureSample, Wraps) {
    const Texture t = twoByTwo();
    // u = 0 lies between A's left neighbour (B, wrapped) and A.
    expectNear(t.sample({0.0f, 0.75f}), (kA + kB) * 0.5f);
    expectNear(t.sample({1.25f, -0.75f}), kC);
    expectNear(t.sample({-0.75f, 2.75f}), kA);
}

// glTF samplers' CLAMP_TO_EDGE: past an edge, the edge texels; MIRRORED_REPEAT: the image
// mirrored at each edge, so that u = 1.25 looks up u = 0.75. Each axis has its own.
TEST(TextureSample, ClampsAndMirrorsAsTheSamplerSays) {
    Texture clamp = twoByTwo();
    clamp.wrapU = clamp.wrapV = TextureWrap::ClampToEdge;
    expectNear(clamp.sample({0.0f, 0.75f}), kA);  // not half of the other edge's B
    expectNear(clamp.sample({-3.0f, 0.75f}), kA);
    expectNear(clamp.sample({7.5f, 9.0f}), kB);                 // far past the top right
    expectNear(clamp.sample({0.25f, -1e6f}), kC);               // far below: the bottom row
    expectNear(clamp.sample({0.5f, 0.75f}), (kA + kB) * 0.5f);  // inside, as before
    Texture mirror = twoByTwo();
    mirror.wrapU = mirror.wrapV = TextureWrap::MirroredRepeat;
    expectNear(mirror.sample({1.25f, 0.75f}), kB);  // u 0.75 mirrored: B
    expectNear(mirror.sample({1.75f, 0.75f}), kA);
    expectNear(mirror.sample({-0.25f, 0.75f}), kA);  // mirrored at u = 0
    expectNear(mirror.sample({1.0f, 0.75f}), kB);    // the edge: B and its mirror image
    expectNear(mirror.sample({0.25f, 1.25f}), kA);   // v 0.75
    expectNear(mirror.sample({2.25f, 0.75f}), kA);   // one whole period further
    Texture mixed = twoByTwo();
    mixed.wrapU = TextureWrap::ClampToEdge;  // v still repeats
    expectNear(mixed.sample({1.5f, 1.25f}), kD);
    expectNear(mixed.sample({0.0f, 0.75f}), kA);
}

TEST(DecodeTexture, PpmIsReadTopRowFirstAndLinearized) {
    DiskFileSource disk(test::testdataDir() / "minimal");
    const Texture t = decodeTexture("checker.ppm", disk.read("checker.ppm"));
    ASSERT_EQ(t.width, 2);
    ASSERT_EQ(t.height, 2);
    expectNear(t.texels[0], kA);
    expectNear(t.texels[1], kB);
    expectNear(t.texels[2], kC);
    // sRGB 128/255 is 0.2158 in linear light, not 0.502.
    EXPECT_NEAR(t.texels[3].x, 0.21586f, 1e-4f);
    expectNear(t.average, (kA + kB + kC + t.texels[3]) * 0.25f);
}

// A 1 x 2 grey image (white above black) encoded by OpenImageIO in the format of `ext`.
std::string greyImageBytes(const std::string& ext) {
    const auto path = testing::scratchPath("grey." + ext);
    auto out = OIIO::ImageOutput::create(path.string());
    EXPECT_TRUE(out);
    if (!out) return "";
    const OIIO::ImageSpec spec(1, 2, 1, OIIO::TypeDesc::UINT8);
    EXPECT_TRUE(out->open(path.string(), spec));
    const unsigned char pixels[2] = {255, 0};
    EXPECT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels));
    out->close();
    std::ifstream in(path, std::ios::binary);
    std::stringstream bytes;
    bytes << in.rdbuf();
    std::filesystem::remove(path);
    return bytes.str();
}

// PNG decodes from memory; SGI has no IOProxy reader and goes through a temporary file.
TEST(DecodeTexture, FromMemoryOrTemporaryFileWithGreyReplicated) {
    for (const std::string ext : {"png", "sgi"}) {
        SCOPED_TRACE(ext);
        const Texture t = decodeTexture("grey." + ext, greyImageBytes(ext));
        ASSERT_EQ(t.width, 1);
        ASSERT_EQ(t.height, 2);
        expectNear(t.texels[0], glm::vec3(1.0f));
        expectNear(t.texels[1], glm::vec3(0.0f));
        expectNear(t.average, glm::vec3(0.5f));
    }
    // The temporary copies are gone.
    for (const auto& entry :
         std::filesystem::directory_iterator(std::filesystem::temp_directory_path())) {
        EXPECT_EQ(entry.path().filename().string().rfind(
                      "igi-texture-" + std::to_string(::getpid()) + "-", 0),
                  std::string::npos);
    }
}

TEST(DecodeTexture, GarbageIsAnErrorNamingTheFile) {
    const std::string what = test::sceneErrorOf([] { decodeTexture("broken.png", "not a png"); });
    EXPECT_NE(what.find("broken.png"), std::string::npos) << what;
}

TEST(LocateFile, FindsANameThatDiffersInCase) {
    BundleFileSource files(std::map<std::string, std::string>{{"tex/Stone.JPG", "x"}});
    EXPECT_EQ(locateFile(files, "tex/Stone.JPG"), "tex/Stone.JPG");
    EXPECT_EQ(locateFile(files, "tex/STONE.jpg"), "tex/Stone.JPG");
    EXPECT_EQ(locateFile(files, "tex/other.jpg"), std::nullopt);
    EXPECT_EQ(locateFile(files, "Stone.JPG"), std::nullopt);  // another folder
}

}  // namespace
}  // namespace igi
