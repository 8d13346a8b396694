#include "scene/SceneChange.h"

#include <gtest/gtest.h>

namespace igi {
namespace {

SceneState twoObjects() {
    SceneState s;
    s.transforms = {Transform{}, Transform{}};
    s.materials = {Material{}, Material{}};
    s.materials[1].name = "red";
    s.punctualLights = {pointLight("lamp", glm::vec3(0, 2, 0), glm::vec3(1), true)};
    s.quadLights = {QuadLight{"panel", glm::vec3(0), glm::vec3(1, 0, 0), glm::vec3(0, 0, 1),
                              glm::vec3(5), true}};
    return s;
}

TEST(SceneChange, DiffThenApplyReproducesTheTarget) {
    const SceneState from = twoObjects();
    SceneState to = from;
    to.camera.position = glm::vec3(1, 2, 3);
    to.transforms[1].translate = glm::vec3(0.5f, 0, 0);
    to.materials[1].diffuse = glm::vec3(0.9f, 0.1f, 0.1f);
    to.punctualLights[0].on = false;
    to.quadLights[0].radiance = glm::vec3(2);
    const auto changes = diffStates(from, to);
    EXPECT_EQ(changes.size(), 5u);
    SceneState s = from;
    applyChanges(s, changes);
    EXPECT_EQ(s, to);
    EXPECT_TRUE(diffStates(to, to).empty());
}

// The render settings are part of the state: a diff carries them whole, once.
TEST(SceneChange, SettingsAreOneChangeOfTheirOwn) {
    const SceneState from = twoObjects();
    SceneState to = from;
    to.render.indirectVpls = 64;
    to.render.roulette = false;
    const auto changes = diffStates(from, to);
    ASSERT_EQ(changes.size(), 1u);
    EXPECT_TRUE(changesSettings(changes));
    EXPECT_FALSE(changesSettings(diffStates(from, twoObjects())));
    SceneState s = from;
    applyChanges(s, changes);
    EXPECT_EQ(s, to);
    EXPECT_EQ(s.render.indirectVpls, 64);
}

TEST(SceneChange, NamesAndTexturesStayAndBadIndicesChangeNothing) {
    SceneState s = twoObjects();
    s.materials[1].diffuseTexture = 3;
    Material m;
    m.name = "renamed?";
    m.diffuse = glm::vec3(0.2f);
    applyChanges(s, {MaterialChange{1, m}});
    EXPECT_EQ(s.materials[1].name, "red");
    EXPECT_EQ(s.materials[1].diffuseTexture, 3);
    EXPECT_EQ(s.materials[1].diffuse, glm::vec3(0.2f));

    const SceneState before = s;
    EXPECT_THROW(applyChanges(s, {CameraChange{Camera{}}, TransformChange{7, Transform{}}}),
                 std::invalid_argument);
    EXPECT_EQ(s, before);  // the camera change before the bad one did not stick
}

TEST(SceneChange, TheEnvironmentChangesItsRadianceAndRotationButKeepsItsMap) {
    SceneState s = twoObjects();
    s.environment.texture = 2;
    s.environment.radiance = glm::vec3(1.0f);
    SceneState to = s;
    to.environment.radiance = glm::vec3(4.0f, 3.0f, 2.0f);
    to.environment.rotateDeg = 90.0f;
    const auto changes = diffStates(s, to);
    ASSERT_EQ(changes.size(), 1u);
    Environment sent = std::get<EnvironmentChange>(changes[0]).value;
    sent.texture = -1;  // the wire does not carry the map
    applyChanges(s, {EnvironmentChange{sent}});
    EXPECT_EQ(s, to);
    EXPECT_EQ(s.environment.texture, 2);
    EXPECT_FALSE(s.sameLightsAndMaterials(twoObjects()));
}

}  // namespace
}  // namespace igi
