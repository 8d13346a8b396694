// Bad scene files: each error names the file and the line or JSON path, and says what is wrong.

#include <gtest/gtest.h>

#include "util/ExpectContains.h"

#include "scene/SceneLoader.h"
#include "scene/TestScenes.h"

namespace igi {
namespace {

using test::parseInline;
using test::sceneErrorOf;

const char* kLight = R"({"type": "point", "position": [0, 0, 0], "intensity": 1})";

std::string withLight(const std::string& more) {
    return std::string(R"({"lights": [)") + kLight + "]" + (more.empty() ? "" : ", " + more) + "}";
}

// A small valid OBJ + MTL for scenes that need a mesh.
std::map<std::string, std::string> triangleFiles() {
    return {{"t.obj", "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n"},
            {"t.mtl", "newmtl a\nKd 0.5 0.5 0.5\n"}};
}

TEST(SceneJsonErrors, SyntaxErrorGivesLineAndColumn) {
    const std::string what =
        sceneErrorOf([] { parseInline("{\n  \"image\": {\n    \"width\": 12,,\n  }\n}"); });
    EXPECT_CONTAINS(what, "inline.json:3: column 17: ");
    EXPECT_CONTAINS(what, "syntax error");
}

TEST(SceneJsonErrors, TopLevelMustBeAnObject) {
    EXPECT_CONTAINS(sceneErrorOf([] { parseInline("[1, 2]"); }), "inline.json: expected an object");
}

TEST(SceneJsonErrors, UnknownKeyNamesItsPathAndTheAllowedKeys) {
    const std::string what = sceneErrorOf([] {
        parseInline(R"({"meshes": [{"file": "t.obj"}, {"file": "t.obj", "transfrom": {}}]})",
                    triangleFiles());
    });
    EXPECT_CONTAINS(
        what,
        "inline.json: /meshes/1/transfrom: unknown key (expected one of: file, name, transform)");
    EXPECT_CONTAINS(sceneErrorOf([] { parseInline(withLight(R"("imag": {})")); }),
                    "inline.json: /imag: unknown key");
    EXPECT_CONTAINS(sceneErrorOf([] { parseInline(withLight(R"("render": {"sed": 1})")); }),
                    "/render/sed: unknown key");
}

// Issue 40: an unknown key close to a known one (or another program's name for it) says
// which it probably is.
TEST(SceneJsonErrors, UnknownKeySuggestsTheKnownOneMeant) {
    EXPECT_CONTAINS(sceneErrorOf([] { parseInline(withLight(R"("render": {"spp": 4})")); }),
                    "/render/spp: unknown key (expected one of: ");
    EXPECT_CONTAINS(sceneErrorOf([] { parseInline(withLight(R"("render": {"spp": 4})")); }),
                    "; did you mean 'path_samples'?");
    EXPECT_CONTAINS(sceneErrorOf([] {
                        parseInline(R"({"meshes": [{"file": "t.obj", "transfrom": {}}]})",
                                    triangleFiles());
                    }),
                    "did you mean 'transform'?");
    const std::string far =
        sceneErrorOf([] { parseInline(withLight(R"("render": {"banana": 1})")); });
    EXPECT_EQ(far.find("did you mean"), std::string::npos) << far;
}

TEST(SceneJsonErrors, OverflowingNumbersAreRejected) {
    EXPECT_CONTAINS(sceneErrorOf([] {
                        parseInline(R"({"image": {"width": 10, "height": 10,
                                                              "exposure": -1e999}})");
                    }),
                    "inline.json:2: column 75: number -1e999 overflows (not finite)");
    // Finite as a double, infinite as a float.
    EXPECT_CONTAINS(
        sceneErrorOf([] {
            parseInline(
                R"({"lights": [{"type": "point", "position": [0, 1e300, 0], "intensity": 1}]})");
        }),
        "/lights/0/position/1: number 1e+300 is too large");
}

TEST(SceneJsonErrors, ImageSizeMustBePositiveIntegers) {
    EXPECT_CONTAINS(
        sceneErrorOf([] { parseInline(withLight(R"("image": {"width": -5, "height": 10})")); }),
        "/image/width: must be in [1, 16384], got -5");
    EXPECT_CONTAINS(
        sceneErrorOf([] { parseInline(withLight(R"("image": {"width": 10, "height": 0})")); }),
        "/image/height: must be in [1, 16384], got 0");
    EXPECT_CONTAINS(
        sceneErrorOf([] { parseInline(withLight(R"("image": {"width": 10.5, "height": 10})")); }),
        "/image/width: expected an integer");
    EXPECT_CONTAINS(sceneErrorOf([] { parseInline(withLight(R"("image": {"width": 10})")); }),
                    "/image: missing required key 'height'");
}

TEST(SceneJsonErrors, DegenerateCameras) {
    EXPECT_CONTAINS(
        sceneErrorOf([] {
            parseInline(withLight(R"("camera": {"position": [1, 2, 3], "look_at": [1, 2, 3]})"));
        }),
        "/camera/look_at: look_at equals position");
    EXPECT_CONTAINS(
        sceneErrorOf([] {
            parseInline(withLight(
                R"("camera": {"position": [0, 0, 0], "look_at": [0, 5, 0], "up": [0, 2, 0]})"));
        }),
        "/camera/up: up is parallel to the view direction");
    EXPECT_CONTAINS(
        sceneErrorOf([] {
            parseInline(withLight(
                R"("camera": {"position": [0, 0, 0], "look_at": [0, 0, 1], "up": [0, 0, 0]})"));
        }),
        "/camera/up: up is the zero vector");
    EXPECT_CONTAINS(
        sceneErrorOf([] {
            parseInline(withLight(
                R"("camera": {"position": [0, 0, 1], "look_at": [0, 0, 0], "fov_y": 180})"));
        }),
        "/camera/fov_y: must be in (0, 180), got 180");
}

TEST(SceneJsonErrors, MissingMeshFile) {
    EXPECT_CONTAINS(sceneErrorOf([] { parseInline(R"({"meshes": [{"file": "nope.obj"}]})"); }),
                    "inline.json: /meshes/0/file: file 'nope.obj' not found");
    EXPECT_CONTAINS(sceneErrorOf([] { parseInline(R"({"meshes": [{"file": "x.ply"}]})"); }),
                    "/meshes/0/file: unsupported mesh format '.ply'");
}

TEST(SceneJsonErrors, BadSpotAndDirectionalLightsNameTheKey) {
    EXPECT_CONTAINS(sceneErrorOf([] {
                        parseInline(R"({"lights": [{"type": "directional", "direction": [0, 0, 0],
                                        "irradiance": 1}]})");
                    }),
                    "/lights/0/direction: direction is the zero vector");
    EXPECT_CONTAINS(sceneErrorOf([] {
                        parseInline(R"({"lights": [{"type": "spot", "position": [0, 1, 0],
                                        "direction": [0, -1, 0], "intensity": 1,
                                        "inner_deg": 50, "outer_deg": 40}]})");
                    }),
                    "/lights/0/inner_deg: inner_deg 50.000000 exceeds outer_deg 40.000000");
    EXPECT_CONTAINS(sceneErrorOf([] {
                        parseInline(R"({"lights": [{"type": "spot", "position": [0, 1, 0],
                                        "direction": [0, -1, 0], "intensity": 1,
                                        "outer_deg": 95}]})");
                    }),
                    "/lights/0/outer_deg");
    EXPECT_CONTAINS(sceneErrorOf([] {
                        parseInline(R"({"lights": [{"type": "directional", "direction": [0, -1, 0],
                                        "irradiance": 1, "angle_deg": 45}]})");
                    }),
                    "/lights/0/angle_deg");
    EXPECT_CONTAINS(sceneErrorOf([] {
                        parseInline(R"({"lights": [{"type": "directional", "direction": [0, -1, 0],
                                        "intensity": 1}]})");
                    }),
                    "/lights/0/intensity: unknown key");
}

TEST(SceneJsonErrors, BadTypes) {
    EXPECT_CONTAINS(sceneErrorOf([] {
                        parseInline(R"({"lights": [{"type": "area", "position": [0, 0, 0]}]})");
                    }),
                    "/lights/0/type: unknown value 'area' (expected one of: point, spot, "
                    "directional, quad)");
    EXPECT_CONTAINS(
        sceneErrorOf([] {
            parseInline(R"({"meshes": [{"file": "t.obj"}], "materials": {"a": {"type": "metal"}}})",
                        triangleFiles());
        }),
        "/materials/a/type: unknown value 'metal' (expected one of: diffuse, glossy, mirror, "
        "glass, rough_glass, metallic_roughness)");
    EXPECT_CONTAINS(
        sceneErrorOf([] { parseInline(withLight(R"("render": {"integrator": "bdpt"})")); }),
        "/render/integrator: unknown value 'bdpt'");
    EXPECT_CONTAINS(sceneErrorOf([] { parseInline(withLight(R"("headlight": "yes")")); }),
                    "/headlight: expected true or false");
    EXPECT_CONTAINS(
        sceneErrorOf([] {
            parseInline(R"({"lights": [{"type": "point", "position": [0, 0], "intensity": 1}]})");
        }),
        "/lights/0/position: expected an array of 3 elements, got 2");
}

TEST(SceneJsonErrors, LightsOutOfRangeOrDegenerate) {
    EXPECT_CONTAINS(
        sceneErrorOf([] {
            parseInline(
                R"({"lights": [{"type": "point", "position": [0, 0, 0], "intensity": [1, -1, 1]}]})");
        }),
        "/lights/0/intensity/1: must be in [0, inf]");
    EXPECT_CONTAINS(
        sceneErrorOf([] {
            parseInline(R"({"lights": [{"type": "quad", "corner": [0, 0, 0], "edge1": [1, 0, 0],
                                                    "edge2": [2, 0, 0], "radiance": 1}]})");
        }),
        "/lights/0/edge2: edge2 is parallel to edge1");
    EXPECT_CONTAINS(
        sceneErrorOf([] {
            parseInline(R"({"lights": [{"type": "quad", "corner": [0, 0, 0], "edge1": [0, 0, 0],
                                                    "edge2": [2, 0, 0], "radiance": 1}]})");
        }),
        "/lights/0/edge1: edge is the zero vector");
    EXPECT_CONTAINS(
        sceneErrorOf([] {
            parseInline(
                R"({"lights": [{"type": "point", "position": [0, 0, 0], "intensity": 1, "radiance": 1}]})");
        }),
        "/lights/0/radiance: unknown key (expected one of: type, name, position, intensity)");
}

TEST(SceneJsonErrors, TransformScaleMustNotBeZero) {
    EXPECT_CONTAINS(sceneErrorOf([] {
                        parseInline(
                            R"({"meshes": [{"file": "t.obj", "transform": {"scale": [1, 0, 1]}}]})",
                            triangleFiles());
                    }),
                    "/meshes/0/transform/scale: scale must not be zero");
    EXPECT_CONTAINS(sceneErrorOf([] {
                        parseInline(R"({"meshes": [{"file": "t.obj", "transform": {"scale": 0}}]})",
                                    triangleFiles());
                    }),
                    "/meshes/0/transform/scale: scale must not be zero");
}

TEST(SceneJsonErrors, OverrideOfAnUnknownMaterialOrTexture) {
    EXPECT_CONTAINS(sceneErrorOf([] {
                        parseInline(R"({"meshes": [{"file": "t.obj"}], "materials": {"b": {}}})",
                                    triangleFiles());
                    }),
                    "/materials/b: no loaded mesh has a material named 'b'");
    EXPECT_CONTAINS(
        sceneErrorOf([] {
            parseInline(
                R"({"meshes": [{"file": "t.obj"}], "materials": {"a": {"texture": "x.png"}}})",
                triangleFiles());
        }),
        "/materials/a/texture: texture 'x.png' not found");
    EXPECT_CONTAINS(
        sceneErrorOf([] {
            parseInline(
                R"({"meshes": [{"file": "t.obj"}], "materials": {"a": {"diffuse": [2, 0, 0]}}})",
                triangleFiles());
        }),
        "/materials/a/diffuse/0: must be in [0, 1], got 2");
    EXPECT_CONTAINS(sceneErrorOf([] {
                        parseInline(
                            R"({"meshes": [{"file": "t.obj"}], "materials": {"a": {"ior": 0}}})",
                            triangleFiles());
                    }),
                    "/materials/a/ior: must be in (0, inf]");
}

TEST(SceneJsonErrors, NothingToFrame) {
    EXPECT_CONTAINS(sceneErrorOf([] { parseInline("{}"); }),
                    "inline.json: no camera given and nothing to frame");
}

}  // namespace
}  // namespace igi
