// A live change of the environment (its scale or radiance, its rotation) as the client applies
// it: the same map under another factor keeps its sampling tables, a rotation turns the
// mapping alone, another colour balance builds tables of its own (issue 35).

#include <gtest/gtest.h>

#include "lights/Lights.h"
#include "math/Color.h"
#include "math/Warp.h"
#include "scene/SceneChange.h"
#include "testing/TestScenes.h"
#include "tracing/EnvironmentMap.h"

namespace igi {
namespace {

// An 8 x 4 map whose texels all differ, brightest in the warm top rows.
Texture gradientSky() {
    Texture t;
    t.path = "gradient.exr";
    t.width = 8;
    t.height = 4;
    for (int y = 0; y < t.height; ++y)
        for (int x = 0; x < t.width; ++x)
            t.texels.push_back(glm::vec3(4.0f - float(y) + 0.1f * float(x), 1.0f + 0.2f * float(y),
                                         0.5f + 0.05f * float(x)));
    return t;
}

Environment mapOf(glm::vec3 factor, float rotateDeg = 0.0f) {
    Environment e;
    e.texture = 0;
    e.radiance = factor;
    e.rotateDeg = rotateDeg;
    return e;
}

std::vector<glm::vec3> someDirections() {
    std::vector<glm::vec3> d;
    for (int i = 0; i < 64; ++i)
        d.push_back(
            squareToUniformSphere({(float(i) + 0.5f) / 64.0f, float((i * 37) % 64) / 64.0f}));
    return d;
}

TEST(EnvironmentChange, ANewScaleScalesTheRadianceAndKeepsTheDensity) {
    const std::vector<Texture> textures = {gradientSky()};
    const EnvironmentMap loaded(mapOf(glm::vec3(1.0f)), textures);
    const EnvironmentMap scaled = loaded.changedTo(mapOf(glm::vec3(4.0f)), textures);
    ASSERT_TRUE(scaled.present());
    for (const glm::vec3 d : someDirections()) {
        EXPECT_EQ(scaled.radiance(d), 4.0f * loaded.radiance(d));
        EXPECT_EQ(scaled.pdf(d), loaded.pdf(d));
    }
    // The same samples, four times as bright: the light's power (its selection among other
    // lights) scales with it.
    const EnvironmentMap::Sample a = loaded.sample({0.3f, 0.6f}), b = scaled.sample({0.3f, 0.6f});
    EXPECT_EQ(a.toSky, b.toSky);
    EXPECT_EQ(a.pdf, b.pdf);
    EXPECT_EQ(b.radiance, 4.0f * a.radiance);
    EXPECT_FLOAT_EQ(scaled.meanLuminance(), 4.0f * loaded.meanLuminance());
    // Built from scratch at that scale, the tables agree to rounding.
    const EnvironmentMap fresh(mapOf(glm::vec3(4.0f)), textures);
    for (const glm::vec3 d : someDirections()) EXPECT_NEAR(fresh.pdf(d) / scaled.pdf(d), 1.0, 1e-5);
    EXPECT_FLOAT_EQ(fresh.meanLuminance(), scaled.meanLuminance());
}

TEST(EnvironmentChange, ARotationTurnsTheMappingAndItsDensityAlike) {
    const std::vector<Texture> textures = {gradientSky()};
    const EnvironmentMap loaded(mapOf(glm::vec3(1.0f)), textures);
    const EnvironmentMap turned = loaded.changedTo(mapOf(glm::vec3(1.0f), 60.0f), textures);
    for (const glm::vec3 d : someDirections()) {
        const glm::vec3 t = turnAboutUp(d, 60.0f);
        EXPECT_EQ(turned.radiance(t), loaded.radiance(d));
        EXPECT_NEAR(turned.pdf(t), loaded.pdf(d), 1e-6f * loaded.pdf(d));
    }
    EXPECT_EQ(turned.meanLuminance(), loaded.meanLuminance());
}

TEST(EnvironmentChange, AnotherColourBalanceOrABlackMapGetsTablesOfItsOwn) {
    const std::vector<Texture> textures = {gradientSky()};
    const EnvironmentMap loaded(mapOf(glm::vec3(1.0f)), textures);
    const Environment blue = mapOf({0.1f, 0.1f, 3.0f});
    const EnvironmentMap changed = loaded.changedTo(blue, textures);
    const EnvironmentMap fresh(blue, textures);
    for (const glm::vec3 d : someDirections()) EXPECT_EQ(changed.pdf(d), fresh.pdf(d));
    EXPECT_EQ(changed.meanLuminance(), fresh.meanLuminance());
    // A map loaded at scale 0 lights nothing until a change gives it a scale.
    const EnvironmentMap black(mapOf(glm::vec3(0.0f)), textures);
    EXPECT_FALSE(black.present());
    const EnvironmentMap lit = black.changedTo(mapOf(glm::vec3(2.0f)), textures);
    EXPECT_TRUE(lit.present());
    EXPECT_FLOAT_EQ(lit.meanLuminance(),
                    EnvironmentMap(mapOf(glm::vec3(2.0f)), textures).meanLuminance());
    EXPECT_FALSE(lit.changedTo(mapOf(glm::vec3(0.0f)), textures).present());
}

// A scene state's environment is what its traceable scene shows and its lights sample; the
// file's map stays, and the epochs after a change share what the change built.
TEST(EnvironmentChange, AStatesEnvironmentIsWhatItsSceneShowsAndItsLightsCarry) {
    Scene scene;
    scene.materials.push_back(testing::diffuse(glm::vec3(0.5f)));
    scene.meshes.push_back(testing::makeQuad({-1, 0, -1}, {0, 0, 2}, {2, 0, 0}, 0));
    scene.textures.push_back(gradientSky());
    scene.environment = mapOf(glm::vec3(1.0f));
    EmbreeDevice device;
    SceneGeometry geometry(device, scene);
    SceneState state = SceneState::of(scene);
    const TraceableScene before(geometry, state);
    const Lights lightsBefore(before, state.punctualLights);
    applyChanges(state, {EnvironmentChange{mapOf(glm::vec3(8.0f), 30.0f)}});
    EXPECT_EQ(state.environment.texture, 0);
    const TraceableScene after(geometry, state);
    const Lights lightsAfter(after, state.punctualLights);
    const glm::vec3 d = glm::normalize(glm::vec3(0.3f, 0.8f, -0.2f));
    EXPECT_EQ(after.skyRadiance(turnAboutUp(d, 30.0f)), 8.0f * before.skyRadiance(d));
    EXPECT_NEAR(lightsAfter.totalPower() / lightsBefore.totalPower(), 8.0, 1e-5);
    // The next epoch (the camera moved) finds the same tables.
    state.camera.position.x += 1.0f;
    const TraceableScene next(geometry, state);
    EXPECT_EQ(next.environment().pdf(d), after.environment().pdf(d));
    // Back to the file's: the environment as loaded, exactly.
    state.environment = scene.environment;
    const TraceableScene back(geometry, state);
    EXPECT_EQ(back.skyRadiance(d), before.skyRadiance(d));
}

// A scene without an environment gets a constant sky from a change of its radiance.
TEST(EnvironmentChange, AConstantSkyCanBeSwitchedOnLive) {
    Scene scene;
    scene.materials.push_back(testing::diffuse(glm::vec3(0.5f)));
    scene.meshes.push_back(testing::makeQuad({-1, 0, -1}, {0, 0, 2}, {2, 0, 0}, 0));
    EmbreeDevice device;
    SceneGeometry geometry(device, scene);
    SceneState state = SceneState::of(scene);
    Environment sky;
    sky.radiance = glm::vec3(0.5f, 1.0f, 2.0f);
    applyChanges(state, {EnvironmentChange{sky}});
    const TraceableScene lit(geometry, state);
    EXPECT_TRUE(lit.hasSky());
    EXPECT_EQ(lit.skyRadiance({0, 1, 0}), sky.radiance);
    const Lights lights(lit, state.punctualLights);
    EXPECT_FALSE(lights.empty());
}

}  // namespace
}  // namespace igi
