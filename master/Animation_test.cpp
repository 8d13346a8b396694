#include "Animation.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "scene/SceneError.h"
#include "scene/SceneLoader.h"
#include "util/TestPaths.h"

namespace igi {
namespace {

Mesh mesh(const std::string& name) {
    Mesh m;
    m.name = name;
    return m;
}

Material material(const std::string& name, glm::vec3 diffuse) {
    Material m;
    m.name = name;
    m.diffuse = diffuse;
    return m;
}

// A scene with every kind of name the animation resolves, and the ambiguous ones.
Scene testScene() {
    Scene s;
    s.camera.position = {0, 1, 3.4f};
    s.camera.lookAt = {0, 1, 0};
    s.camera.fovYDeg = 40;
    s.meshes = {mesh("room"), mesh("glass_ball"), mesh("twin"), mesh("twin")};
    s.meshes[1].transform.translate = {0.4f, 0.36f, 0.3f};
    s.meshes[1].transform.scale = glm::vec3(0.36f);
    s.materials = {material("white", glm::vec3(0.7f)), material("red", {0.63f, 0.065f, 0.05f}),
                   material("white", glm::vec3(0.5f)), material("mirror", glm::vec3(0))};
    s.materials[2].diffuseTexture = 0;
    s.materials[3].reflection = Reflection::Mirror;
    s.materials[3].specular = glm::vec3(0.9f);
    s.punctualLights = {pointLight("lamp", {0, 1.5f, 1.5f}, glm::vec3(0.2f), true),
                        pointLight("dup", {0, 0, 0}, glm::vec3(1), true)};
    s.quadLights = {QuadLight{"ceiling_light",
                              {-0.25f, 1.98f, -0.2f},
                              {0.5f, 0, 0},
                              {0, 0, 0.4f},
                              {17, 13.5f, 9},
                              true},
                    QuadLight{"dup", {0, 0, 0}, {1, 0, 0}, {0, 0, 1}, glm::vec3(1), true}};
    return s;
}

Animation parse(const std::string& text) {
    return Animation::parse(text, "test.anim.json", testScene());
}

SceneState stateAt(const Animation& a, std::uint32_t frame) {
    return a.stateAt(frame, SceneState::of(testScene()));
}

// The SceneError that parsing `text` throws (a test failure if none).
SceneError errorOf(const std::string& text) {
    try {
        parse(text);
    } catch (const SceneError& e) {
        return e;
    }
    ADD_FAILURE() << "expected a SceneError for " << text;
    return SceneError::inFile("", "none");
}

void expectVec(glm::vec3 actual, glm::vec3 expected) {
    EXPECT_NEAR(actual.x, expected.x, 1e-5f);
    EXPECT_NEAR(actual.y, expected.y, 1e-5f);
    EXPECT_NEAR(actual.z, expected.z, 1e-5f);
}

TEST(Animation, InterpolatesAtBetweenBeforeAndAfterKeys) {
    const Animation a = parse(R"({"camera": [
        {"frame": 10, "position": [0, 1, 5]},
        {"frame": 20, "position": [10, 1, 5]}]})");
    expectVec(stateAt(a, 0).camera.position, {0, 1, 5});  // before the first: holds the first
    EXPECT_EQ(stateAt(a, 10).camera.position, glm::vec3(0, 1, 5));  // exactly the key
    expectVec(stateAt(a, 15).camera.position, {5, 1, 5});
    expectVec(stateAt(a, 12).camera.position, {2, 1, 5});
    EXPECT_EQ(stateAt(a, 20).camera.position, glm::vec3(10, 1, 5));
    EXPECT_EQ(stateAt(a, 1000).camera.position, glm::vec3(10, 1, 5));  // after the last: holds
    // What the animation does not key comes from the base.
    EXPECT_EQ(stateAt(a, 15).camera.lookAt, glm::vec3(0, 1, 0));
    EXPECT_EQ(stateAt(a, 15).camera.fovYDeg, 40.0f);
}

TEST(Animation, TheEnvironmentsScaleAndRotationInterpolate) {
    const Animation a = parse(R"({"environment": [
        {"frame": 0, "scale": 1, "rotate_deg": 0},
        {"frame": 10, "scale": [3, 5, 1], "rotate_deg": 90}]})");
    EXPECT_FALSE(a.empty());
    EXPECT_EQ(a.lastKeyFrame(), 10u);
    const Environment e = stateAt(a, 5).environment;
    expectVec(e.radiance, {2, 3, 1});
    EXPECT_NEAR(e.rotateDeg, 45.0f, 1e-4f);
    EXPECT_EQ(stateAt(a, 20).environment.radiance, glm::vec3(3, 5, 1));
    EXPECT_EQ(errorOf(R"({"environment": [{"frame": 0, "scale": -2}]})").jsonPath(),
              "/environment/0/scale");
    EXPECT_EQ(errorOf(R"({"environment": [{"frame": 0, "exposure": 2}]})").jsonPath(),
              "/environment/0/exposure");
}

TEST(Animation, EachPropertyInterpolatesBetweenTheKeysThatMentionIt) {
    const Animation a = parse(R"({"camera": [
        {"frame": 0, "position": [0, 1, 4], "fov_y": 40},
        {"frame": 10, "position": [2, 1, 4]},
        {"frame": 40, "fov_y": 80, "look_at": [0, 2, 0]}]})");
    const Camera c = stateAt(a, 20).camera;
    expectVec(c.position, {2, 1, 4});      // its last key is frame 10: holds
    EXPECT_NEAR(c.fovYDeg, 60.0f, 1e-4f);  // keys 0 and 40, not 10
    expectVec(c.lookAt, {0, 2, 0});        // only key 40: holds it from the start
    expectVec(stateAt(a, 5).camera.position, {1, 1, 4});
    EXPECT_NEAR(stateAt(a, 5).camera.fovYDeg, 45.0f, 1e-4f);
}

TEST(Animation, UnanimatedPropertiesComeFromTheGivenBase) {
    const Animation a = parse(R"({"camera": [{"frame": 0, "fov_y": 30}]})");
    SceneState base = SceneState::of(testScene());
    base.camera.position = {1, 2, 3};
    base.materials[1].diffuse = glm::vec3(0.25f);
    const SceneState s = a.stateAt(5, base);
    EXPECT_EQ(s.camera.position, glm::vec3(1, 2, 3));
    EXPECT_EQ(s.camera.fovYDeg, 30.0f);
    EXPECT_EQ(s.materials[1].diffuse, glm::vec3(0.25f));
}

TEST(Animation, ObjectTransformsInterpolatePerAxis) {
    const Animation a = parse(R"({"objects": {"glass_ball": [
        {"frame": 0, "translate": [0.4, 0.36, 0.3], "rotate_deg": [0, 0, 0], "scale": 0.36},
        {"frame": 30, "translate": [-0.4, 0.36, 0.3], "rotate_deg": [0, 90, 360], "scale": [0.36, 0.72, 1]}]}})");
    const Transform t = stateAt(a, 15).transforms[1];
    expectVec(t.translate, {0, 0.36f, 0.3f});
    expectVec(t.rotateDeg, {0, 45, 180});  // per axis, not the shortest rotation
    expectVec(t.scale, {0.36f, 0.54f, 0.68f});
    EXPECT_EQ(stateAt(a, 15).transforms[0], Transform{});  // the room does not move
}

TEST(Animation, BooleansAndMaterialTypesStep) {
    const Animation a = parse(R"({
        "lights": {"ceiling_light": [
            {"frame": 0, "radiance": [10, 10, 10], "on": true},
            {"frame": 20, "on": false},
            {"frame": 40, "on": true, "radiance": [20, 20, 20]}],
          "lamp": [{"frame": 5, "on": false}]},
        "materials": {"red": [
            {"frame": 0, "type": "mirror", "diffuse": 0.2},
            {"frame": 10, "type": "glass", "diffuse": 0.4}]}})");
    EXPECT_TRUE(stateAt(a, 19).quadLights[0].on);
    EXPECT_FALSE(stateAt(a, 20).quadLights[0].on);
    EXPECT_FALSE(stateAt(a, 39).quadLights[0].on);
    EXPECT_TRUE(stateAt(a, 40).quadLights[0].on);
    // Radiance is keyed at 0 and 40 only: it interpolates across the "on" keys.
    expectVec(stateAt(a, 20).quadLights[0].radiance, glm::vec3(15));
    EXPECT_FALSE(stateAt(a, 0).punctualLights[0].on);  // its only key, held before
    EXPECT_TRUE(stateAt(a, 0).punctualLights[1].on);   // another light of the scene

    const Material at9 = stateAt(a, 9).materials[1];
    EXPECT_EQ(at9.reflection, Reflection::Mirror);
    EXPECT_FALSE(at9.glass);
    EXPECT_NEAR(at9.diffuse.x, 0.38f, 1e-5f);
    const Material at10 = stateAt(a, 10).materials[1];
    EXPECT_TRUE(at10.glass);
    EXPECT_EQ(at10.reflection, Reflection::None);
}

TEST(Animation, BeforeTheFirstKeyABooleanHoldsTheFirstKeysValue) {
    const Animation a = parse(
        R"({"lights": {"ceiling_light": [{"frame": 10, "on": false}, {"frame": 20, "on": true}]}})");
    EXPECT_FALSE(stateAt(a, 0).quadLights[0].on);  // not the base's true
    EXPECT_FALSE(stateAt(a, 15).quadLights[0].on);
    EXPECT_TRUE(stateAt(a, 25).quadLights[0].on);
}

TEST(Animation, AMaterialNameChangesEveryMaterialOfThatName) {
    const Animation a = parse(R"({"materials": {"white": [
        {"frame": 0, "specular": 0.1}, {"frame": 10, "specular": 0.3}]}})");
    const SceneState s = stateAt(a, 5);
    expectVec(s.materials[0].specular, glm::vec3(0.2f));
    expectVec(s.materials[2].specular, glm::vec3(0.2f));
    // Each keeps its own other fields.
    EXPECT_EQ(s.materials[0].diffuse, glm::vec3(0.7f));
    EXPECT_EQ(s.materials[2].diffuse, glm::vec3(0.5f));
    EXPECT_EQ(s.materials[2].diffuseTexture, 0);
    EXPECT_EQ(s.materials[1], testScene().materials[1]);
}

TEST(Animation, MaterialsReflectingMoreThanAllTheLightAreScaledDown) {
    // The mirror reflects 0.9 specularly; a diffuse of 0.6 would make 1.5.
    const Animation a = parse(R"({"materials": {"mirror": [{"frame": 0, "diffuse": 0.6}]}})");
    const Material m = stateAt(a, 0).materials[3];
    EXPECT_NEAR(m.diffuse.x + m.specular.x, 1.0f, 1e-5f);
    EXPECT_NEAR(m.diffuse.x / m.specular.x, 0.6f / 0.9f, 1e-5f);
}

TEST(Animation, NamesResolveToTheSceneOrFailNamingThem) {
    const Animation a = parse(R"({"lights": {"lamp": [{"frame": 0, "intensity": 3}]}})");
    EXPECT_EQ(stateAt(a, 0).punctualLights[0].intensity, glm::vec3(3));
    EXPECT_EQ(stateAt(a, 0).punctualLights[1].intensity, glm::vec3(1));

    SceneError e = errorOf(R"({"objects": {"nope": [{"frame": 0, "scale": 2}]}})");
    EXPECT_EQ(e.jsonPath(), "/objects/nope");
    EXPECT_NE(e.message().find("no mesh named 'nope'"), std::string::npos) << e.what();
    EXPECT_NE(e.message().find("room, glass_ball, twin"), std::string::npos) << e.what();

    e = errorOf(R"({"objects": {"twin": [{"frame": 0, "scale": 2}]}})");
    EXPECT_EQ(e.jsonPath(), "/objects/twin");
    EXPECT_NE(e.message().find("2 meshes are named 'twin'"), std::string::npos) << e.what();

    e = errorOf(R"({"lights": {"dup": [{"frame": 0, "on": false}]}})");
    EXPECT_EQ(e.jsonPath(), "/lights/dup");
    EXPECT_NE(e.message().find("2 lights are named 'dup'"), std::string::npos) << e.what();

    e = errorOf(R"({"lights": {"sun": [{"frame": 0, "on": false}]}})");
    EXPECT_EQ(e.jsonPath(), "/lights/sun");
    EXPECT_NE(e.message().find("no light named 'sun'"), std::string::npos) << e.what();

    e = errorOf(R"({"materials": {"blue": [{"frame": 0, "diffuse": 0.1}]}})");
    EXPECT_EQ(e.jsonPath(), "/materials/blue");
    EXPECT_NE(e.message().find("no material named 'blue'"), std::string::npos) << e.what();
    EXPECT_NE(e.message().find("white, red, mirror)"), std::string::npos) << e.what();
}

TEST(Animation, ErrorsNameTheFileAndThePath) {
    struct Case {
        const char* text;
        const char* path;
        const char* message;
    };
    const Case cases[] = {
        {R"({"camera": [{"frame": 5, "fov_y": 30}, {"frame": 5, "fov_y": 40}]})", "/camera/1/frame",
         "strictly increasing"},
        {R"({"camera": [{"frame": 5, "fov_y": 30}, {"frame": 4, "fov_y": 40}]})", "/camera/1/frame",
         "not after the previous keyframe's 5"},
        {R"({"camera": [{"frame": -1, "fov_y": 30}]})", "/camera/0/frame",
         "must be in [0, 1000000]"},
        {R"({"camera": [{"frame": 1.5, "fov_y": 30}]})", "/camera/0/frame", "expected an integer"},
        {R"({"camera": [{"frame": 1000001, "fov_y": 30}]})", "/camera/0/frame", "must be in"},
        {R"({"camera": [{"fov_y": 30}]})", "/camera/0", "missing required key 'frame'"},
        {R"({"camera": [{"frame": 0, "fov_y": 180}]})", "/camera/0/fov_y", "(0, 180)"},
        {R"({"camera": [{"frame": 0, "fov": 30}]})", "/camera/0/fov",
         "unknown key (expected one of: frame, position, look_at, up, fov_y)"},
        {R"({"camera": [{"frame": 0, "position": [0, 1]}]})", "/camera/0/position",
         "expected an array of 3 elements"},
        {R"({"camera": [{"frame": 0, "position": [0, "1", 2]}]})", "/camera/0/position/1",
         "expected a number"},
        {R"({"camera": {"frame": 0}})", "/camera", "expected an array"},
        {R"({"camera": [5]})", "/camera/0", "expected an object"},
        {R"({"camra": []})", "/camra", "unknown key"},
        {R"({"objects": {"glass_ball": [{"frame": 0, "scale": 0}]}})",
         "/objects/glass_ball/0/scale", "scale must not be zero"},
        {R"({"objects": {"glass_ball": [{"frame": 0, "scale": [1, 0, 1]}]}})",
         "/objects/glass_ball/0/scale", "scale must not be zero"},
        {R"({"objects": {"glass_ball": [{"frame": 0, "translat": [0, 0, 0]}]}})",
         "/objects/glass_ball/0/translat", "unknown key (expected one of: frame, translate"},
        {R"({"objects": {"glass_ball": [{"frame": 0, "rotate_deg": [0, 1e300, 0]}]}})",
         "/objects/glass_ball/0/rotate_deg/1", "too large for single precision"},
        {R"({"lights": {"ceiling_light": [{"frame": 0, "radiance": [1, -1, 1]}]}})",
         "/lights/ceiling_light/0/radiance/1", "must be in [0, inf]"},
        {R"({"lights": {"ceiling_light": [{"frame": 0, "on": 1}]}})", "/lights/ceiling_light/0/on",
         "expected true or false"},
        {R"({"lights": {"ceiling_light": [{"frame": 0, "intensity": 1}]}})",
         "/lights/ceiling_light/0/intensity",
         "unknown key (expected one of: frame, corner, edge1, edge2, radiance, on)"},
        {R"({"lights": {"lamp": [{"frame": 0, "corner": [0, 0, 0]}]}})", "/lights/lamp/0/corner",
         "unknown key (expected one of: frame, position, intensity, irradiance, direction, "
         "inner_deg, "
         "outer_deg, angle_deg, on)"},
        {R"({"lights": {"ceiling_light": [{"frame": 0, "edge1": [0, 0, 0]}]}})",
         "/lights/ceiling_light/0/edge1", "edge is the zero vector"},
        {R"({"lights": {"ceiling_light": [{"frame": 0, "edge2": [1, 0, 0]}]}})",
         "/lights/ceiling_light/0/edge2", "parallel to edge1"},
        {R"({"materials": {"red": [{"frame": 0, "diffuse": 1.5}]}})", "/materials/red/0/diffuse",
         "must be in [0, 1]"},
        {R"({"materials": {"red": [{"frame": 0, "ior": 0}]}})", "/materials/red/0/ior",
         "must be in (0, inf]"},
        {R"({"materials": {"red": [{"frame": 0, "type": "metal"}]}})", "/materials/red/0/type",
         "unknown value 'metal' (expected one of: diffuse, glossy, mirror, glass, rough_glass, "
         "metallic_roughness)"},
        {R"({"materials": {"red": [{"frame": 0, "texture": "x.png"}]}})",
         "/materials/red/0/texture", "unknown key"},
    };
    for (const Case& c : cases) {
        const SceneError e = errorOf(c.text);
        EXPECT_EQ(e.file(), "test.anim.json") << c.text;
        EXPECT_EQ(e.jsonPath(), c.path) << c.text << "\n" << e.what();
        EXPECT_NE(e.message().find(c.message), std::string::npos) << c.text << "\n" << e.what();
    }
}

TEST(Animation, SyntaxErrorsNameTheLine) {
    const SceneError e = errorOf("{\n\"camera\": [\n{\"frame\": 0, \"fov_y\": NaN}]}");
    EXPECT_EQ(e.file(), "test.anim.json");
    EXPECT_EQ(e.line(), 3);
}

TEST(Animation, DegenerateCamerasAreRefusedAtKeysAndBetweenThem) {
    // At a key: the position is the scene's look_at.
    SceneError e = errorOf(R"({"camera": [{"frame": 3, "position": [0, 1, 0]}]})");
    EXPECT_EQ(e.jsonPath(), "/camera/0/position");
    EXPECT_NE(e.message().find("no view direction"), std::string::npos) << e.what();

    // Between keys: both keys are valid, frame 5 passes through the look_at.
    e = errorOf(
        R"({"camera": [{"frame": 0, "position": [0, 1, -1]}, {"frame": 10, "position": [0, 1, 1]}]})");
    EXPECT_EQ(e.jsonPath(), "/camera");
    EXPECT_NE(e.message().find("at frame 5 "), std::string::npos) << e.what();
    EXPECT_NE(e.message().find("frames 0 and 10"), std::string::npos) << e.what();

    e = errorOf(R"({"camera": [{"frame": 0, "up": [0, 0, 1]}]})");
    EXPECT_EQ(e.jsonPath(), "/camera/0/up");
    EXPECT_NE(e.message().find("parallel to the view direction"), std::string::npos) << e.what();

    // The same keys two frames apart skip the degenerate point: no integer frame hits it.
    EXPECT_NO_THROW(parse(
        R"({"camera": [{"frame": 0, "position": [0, 1, -1]}, {"frame": 1, "position": [0, 1, 1]}]})"));
}

TEST(Animation, ScalesAndQuadEdgesThroughZeroAreRefusedBetweenKeys) {
    SceneError e = errorOf(
        R"({"objects": {"glass_ball": [{"frame": 0, "scale": 1}, {"frame": 4, "scale": -1}]}})");
    EXPECT_EQ(e.jsonPath(), "/objects/glass_ball");
    EXPECT_NE(e.message().find("at frame 2 "), std::string::npos) << e.what();
    EXPECT_NE(e.message().find("scale must not be zero"), std::string::npos) << e.what();

    e = errorOf(
        R"({"lights": {"ceiling_light": [{"frame": 0, "edge1": [1, 0, 0]}, {"frame": 2, "edge1": [-1, 0, 0]}]}})");
    EXPECT_EQ(e.jsonPath(), "/lights/ceiling_light");
    EXPECT_NE(e.message().find("at frame 1 "), std::string::npos) << e.what();
    EXPECT_NE(e.message().find("edge is the zero vector"), std::string::npos) << e.what();
}

TEST(Animation, ABaseThatWouldMakeAnObjectUnusableKeepsTheBaseValue) {
    const Animation a = parse(R"({"camera": [{"frame": 0, "position": [0, 1, 2]}]})");
    SceneState base = SceneState::of(testScene());
    base.camera.lookAt = {0, 1, 2};  // what the animated position would be
    EXPECT_EQ(a.stateAt(0, base).camera, base.camera);
    base.camera.lookAt = {0, 0, 0};
    EXPECT_EQ(a.stateAt(0, base).camera.position, glm::vec3(0, 1, 2));
}

TEST(Animation, StateAtIsAPureFunction) {
    const std::string text = R"({
        "camera": [{"frame": 0, "position": [0, 1, 3.4]}, {"frame": 60, "position": [1, 1, 3]}],
        "objects": {"glass_ball": [{"frame": 0, "rotate_deg": [0, 0, 0]}, {"frame": 30, "rotate_deg": [0, 77, 0]}]},
        "materials": {"red": [{"frame": 0, "diffuse": [0.63, 0.065, 0.05]}, {"frame": 50, "diffuse": [0.1, 0.1, 0.8]}]}})";
    const Animation a = parse(text);
    const Animation b = parse(text);
    const SceneState at17 = stateAt(a, 17);
    for (std::uint32_t f : {60u, 0u, 33u, 17u}) EXPECT_EQ(stateAt(a, f), stateAt(b, f));
    EXPECT_EQ(stateAt(a, 17), at17);
    const Animation copy = a;
    EXPECT_EQ(stateAt(copy, 17), at17);
    EXPECT_NE(stateAt(a, 17), stateAt(a, 18));
}

TEST(Animation, EmptinessAndTheLastKeyFrame) {
    EXPECT_TRUE(parse("{}").empty());
    EXPECT_EQ(parse("{}").lastKeyFrame(), 0u);
    EXPECT_TRUE(parse(R"({"camera": [], "objects": {}})").empty());
    EXPECT_TRUE(Animation().empty());
    const SceneState base = SceneState::of(testScene());
    EXPECT_EQ(parse("{}").stateAt(7, base), base);

    const Animation a = parse(R"({"camera": [{"frame": 60, "fov_y": 30}],
        "lights": {"lamp": [{"frame": 5, "on": false}, {"frame": 75}]}})");
    EXPECT_FALSE(a.empty());
    // A keyframe that sets nothing still counts for the length.
    EXPECT_EQ(a.lastKeyFrame(), 75u);
    EXPECT_FALSE(stateAt(a, 80).punctualLights[0].on);
}

TEST(Animation, RefusesABaseOfAnotherScene) {
    const Animation a = parse(R"({"camera": [{"frame": 0, "fov_y": 30}]})");
    EXPECT_THROW(a.stateAt(0, SceneState{}), std::invalid_argument);
}

TEST(Animation, LoadNamesAMissingFile) {
    try {
        Animation::load("/nonexistent/anim.json", testScene());
        FAIL() << "expected a SceneError";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.file(), "/nonexistent/anim.json");
    }
}

// The example of docs/ANIMATION.md, against the default scene.
TEST(Animation, TheCornellExampleLoadsAndMoves) {
    const auto root = igi::testing::sourceDir();
    const Scene scene = loadSceneFile(root / "scenes" / "cornell" / "cornell.json");
    const Animation a = Animation::load(root / "master" / "testdata" / "cornell.anim.json", scene);
    const SceneState base = SceneState::of(scene);
    EXPECT_EQ(a.lastKeyFrame(), 120u);
    EXPECT_EQ(a.stateAt(0, base).quadLights[0].on, true);
    EXPECT_EQ(a.stateAt(70, base).quadLights[0].on, false);
    EXPECT_NE(a.stateAt(30, base).transforms[2], base.transforms[2]);  // the glass ball
    EXPECT_NE(a.stateAt(60, base).camera, a.stateAt(0, base).camera);
}

}  // namespace
}  // namespace igi

namespace igi {
namespace {

TEST(AnimationExactness, BetweenEqualKeysTheValueIsExactlyTheKey) {
    // A property that holds still must not look changed (a new epoch restarts accumulation).
    Scene scene;
    Mesh mesh;
    mesh.name = "box";
    scene.meshes.push_back(mesh);
    const Animation a = Animation::parse(
        R"({"objects": {"box": [{"frame": 0, "translate": [-0.8, 0.1, 0.3]},
                                {"frame": 7, "translate": [-0.8, 0.1, 0.3]},
                                {"frame": 9, "translate": [0.7, 0.2, 0.9]}]}})",
        "still.json", scene);
    const SceneState base = SceneState::of(scene);
    for (std::uint32_t f = 0; f <= 7; ++f)
        EXPECT_EQ(a.stateAt(f, base).transforms[0].translate, glm::vec3(-0.8f, 0.1f, 0.3f)) << f;
    EXPECT_EQ(a.stateAt(9, base).transforms[0].translate, glm::vec3(0.7f, 0.2f, 0.9f));
    EXPECT_EQ(a.stateAt(8, base).transforms[0].translate,
              a.stateAt(8, base).transforms[0].translate);
}

}  // namespace
}  // namespace igi
