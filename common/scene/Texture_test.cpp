#include "scene/Texture.h"

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

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

// A lookup one or many periods away finds the same texels with the same weights: near the
// image the wrap needs no division, far from it it divides, and both must agree.
TEST(TextureSample, LooksUpTheSameFarFromTheImageAsNearIt) {
    Texture t;
    t.width = 4;
    t.height = 3;
    for (int i = 0; i < 12; ++i) t.texels.push_back(glm::vec3(float(i), float(i * i), 1.0f));
    for (TextureWrap mode : {TextureWrap::Repeat, TextureWrap::MirroredRepeat}) {
        t.wrapU = t.wrapV = mode;
        const float period = mode == TextureWrap::Repeat ? 1.0f : 2.0f;
        // Texel centres, edges and points between them: exact in float, as are the shifts.
        for (float u = -0.5f; u <= 1.5f; u += 0.0625f)
            for (float v : {0.0f, 0.125f, 0.5f, 0.9375f}) {
                const glm::vec3 near = t.sample({u, v});
                for (float k : {-1000.0f, -3.0f, -2.0f, -1.0f, 1.0f, 2.0f, 3.0f, 1000.0f}) {
                    ASSERT_EQ(t.sample({u + k * period, v}), near) << "u " << u << " k " << k;
                    ASSERT_EQ(t.sample({u, v + k * period}), near) << "v " << v << " k " << k;
                }
            }
    }
}

TEST(DecodeTexture, PpmIsReadTopRowFirstAndLinearized) {
    DiskFileSource disk(test::testdataDir() / "minimal");
    const Texture t = decodeTexture("checker.ppm", disk.read("checker.ppm"));
    ASSERT_EQ(t.width, 2);
    ASSERT_EQ(t.height, 2);
    expectNear(t.texel(0), kA);
    expectNear(t.texel(1), kB);
    expectNear(t.texel(2), kC);
    // sRGB 128/255 is 0.2158 in linear light, not 0.502.
    EXPECT_NEAR(t.texel(3).x, 0.21586f, 1e-4f);
    expectNear(t.average, (kA + kB + kC + t.texel(3)) * 0.25f);
}

// The bytes of an image file with `spec` in the format of `ext`, written by OpenImageIO from
// float values (converted to the spec's format as the writer stores it).
std::string imageBytes(const std::string& ext, const OIIO::ImageSpec& spec,
                       const std::vector<float>& values) {
    const auto path = testing::scratchPath("image." + ext);
    auto out = OIIO::ImageOutput::create(path.string());
    EXPECT_TRUE(out);
    if (!out) return "";
    EXPECT_TRUE(out->open(path.string(), spec));
    EXPECT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, values.data()));
    out->close();
    std::ifstream in(path, std::ios::binary);
    std::stringstream bytes;
    bytes << in.rdbuf();
    std::filesystem::remove(path);
    return bytes.str();
}

// A 1 x 2 grey image (white above black) encoded by OpenImageIO in the format of `ext`.
std::string greyImageBytes(const std::string& ext) {
    return imageBytes(ext, OIIO::ImageSpec(1, 2, 1, OIIO::TypeDesc::UINT8), {1.0f, 0.0f});
}

// The pixels are read in the file's own format and converted by the loader (OpenImageIO would
// go through a 64 MB buffer otherwise): each stored format gives the values it holds.
TEST(DecodeTexture, EachStoredFormatGivesItsValues) {
    // One RGB pixel, read back within half a step of the stored format.
    const std::vector<float> values = {0.2f, 0.5f, 1.0f};
    struct Case {
        std::string ext;
        OIIO::TypeDesc format;
        TextureEncoding encoding;
        float tolerance;
    };
    constexpr float k16 = 0.5f / 65535 + 1e-7f;
    const Case cases[] = {
        {"png", OIIO::TypeDesc::UINT8, TextureEncoding::Data, 0.5f / 255 + 1e-6f},
        {"png", OIIO::TypeDesc::UINT16, TextureEncoding::Data, k16},
        {"exr", OIIO::TypeDesc::HALF, TextureEncoding::Colour, 2e-4f},
        {"exr", OIIO::TypeDesc::FLOAT, TextureEncoding::Colour, 0.0f},
        {"tif", OIIO::TypeDesc::UINT16, TextureEncoding::Data, k16},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.ext + " " + c.format.c_str());
        const Texture t = decodeTexture(
            "image." + c.ext, imageBytes(c.ext, OIIO::ImageSpec(1, 1, 3, c.format), values), {},
            c.encoding);
        ASSERT_EQ(t.texelCount(), 1u);
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(t.texel(0)[i], values[i], c.tolerance);
    }
    // A 16-bit colour image is sRGB-encoded: 0.5 is 0.214 in linear light.
    const Texture srgb = decodeTexture(
        "image.png", imageBytes("png", OIIO::ImageSpec(1, 1, 3, OIIO::TypeDesc::UINT16), values));
    EXPECT_NEAR(srgb.texel(0).y, 0.21404f, 1e-4f);
    // Channels of different formats (half and float in one EXR) are converted by OpenImageIO.
    OIIO::ImageSpec mixed(1, 1, 3, OIIO::TypeDesc::HALF);
    mixed.channelformats = {OIIO::TypeDesc::HALF, OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::HALF};
    const Texture m = decodeTexture("mixed.exr", imageBytes("exr", mixed, values));
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(m.texel(0)[i], values[i], 2e-4f);
    // A fifth channel is not read; the first three are the colour, the fourth its alpha.
    OIIO::ImageSpec five(1, 1, 5, OIIO::TypeDesc::UINT16);
    five.alpha_channel = 3;
    const Texture f =
        decodeTexture("five.tif", imageBytes("tif", five, {0.2f, 0.5f, 1.0f, 0.6f, 0.9f}), {},
                      TextureEncoding::Data);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(f.texel(0)[i], values[i], k16);
    ASSERT_EQ(f.alpha.size(), 1u);
    EXPECT_NEAR(f.alpha[0], 0.6f, k16);
}

// 8-bit images are held as codes in tiles of 32 x 32 texels (Texture::codes): each texel is
// the value the file holds, and every lookup gives the very bits of the same image held as
// floats row by row, across tile edges, in every wrap mode.
TEST(DecodeTexture, EightBitImagesInTilesGiveTheFloatImagesLookups) {
    for (const glm::ivec2 size : {glm::ivec2(37, 45), glm::ivec2(3, 70)}) {
        // 37 x 45: tiles, partial at both edges; 3 x 70: narrower than a tile, so rows.
        SCOPED_TRACE(size.x);
        const int w = size.x, h = size.y;
        std::vector<float> values(std::size_t(w) * h * 3);
        std::uint32_t state = 12345u;
        for (float& v : values) {
            state = state * 1664525u + 1013904223u;
            v = float(state >> 24) / 255.0f;
        }
        const std::string png =
            imageBytes("png", OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::UINT8), values);
        for (const TextureEncoding encoding : {TextureEncoding::Colour, TextureEncoding::Data}) {
            const bool colour = encoding == TextureEncoding::Colour;
            SCOPED_TRACE(colour ? "colour" : "data");
            Texture coded = decodeTexture("image.png", png, {}, encoding);
            ASSERT_FALSE(coded.codes.empty());
            ASSERT_TRUE(coded.texels.empty());
            ASSERT_EQ(coded.texelCount(), std::size_t(w) * h);
            Texture rows = coded;  // the same values as floats, row by row
            rows.codes.clear();
            for (std::size_t i = 0; i < coded.texelCount(); ++i) {
                const glm::vec3 t = coded.texel(i);
                rows.texels.push_back(t);
                for (int c = 0; c < 3; ++c) {
                    const float v = values[i * 3 + c];
                    const float expected = !colour         ? v
                                           : v <= 0.04045f ? v / 12.92f
                                                           : std::pow((v + 0.055f) / 1.055f, 2.4f);
                    ASSERT_NEAR(t[c], expected, 1e-6f) << "texel " << i << " channel " << c;
                }
            }
            for (const TextureWrap wrap :
                 {TextureWrap::Repeat, TextureWrap::ClampToEdge, TextureWrap::MirroredRepeat}) {
                coded.wrapU = coded.wrapV = rows.wrapU = rows.wrapV = wrap;
                for (int k = 0; k < 4000; ++k) {
                    // Lookups over three periods either way, many near texel and tile edges.
                    const glm::vec2 uv(float(k % 97) / 32.0f - 1.0f, float(k / 97) / 13.0f - 1.0f);
                    coded.prefetch(uv);  // a hint: must read nothing outside the image
                    ASSERT_EQ(coded.sample(uv), rows.sample(uv)) << uv.x << ", " << uv.y;
                }
            }
            // Lookups that are not finite give the mean, as the float image's do.
            const glm::vec2 nan(std::nanf(""), 0.5f);
            coded.prefetch(nan);
            coded.prefetch({1e30f, -1e30f});
            EXPECT_EQ(coded.sample(nan), rows.sample(nan));
            EXPECT_EQ(coded.sample({1e30f, -1e30f}), rows.sample({1e30f, -1e30f}));
            // Tiles hold whole tiles; rows exactly the texels.
            EXPECT_EQ(coded.codes.size(), w >= 32 ? std::size_t(64 * 64) : std::size_t(w) * h);
        }
    }
}

// PNG decodes from memory; SGI has no IOProxy reader and goes through a temporary file.
TEST(DecodeTexture, FromMemoryOrTemporaryFileWithGreyReplicated) {
    for (const std::string ext : {"png", "sgi"}) {
        SCOPED_TRACE(ext);
        const Texture t = decodeTexture("grey." + ext, greyImageBytes(ext));
        ASSERT_EQ(t.width, 1);
        ASSERT_EQ(t.height, 2);
        expectNear(t.texel(0), glm::vec3(1.0f));
        expectNear(t.texel(1), glm::vec3(0.0f));
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
