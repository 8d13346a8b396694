#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "Messages.h"

namespace igi::proto::test {

/// One message of every type with every field set away from its default, so that a codec
/// that forgets or swaps a field fails the round trip.
inline AuthBytes sampleAuthBytes(std::uint8_t first) {
    AuthBytes b;
    for (std::size_t i = 0; i < b.size(); ++i) b[i] = std::uint8_t(first + 7 * i);
    return b;
}
inline Hello sampleHello() {
    return {kVersion,          "0.1.0-abc123",     12,
            "render-07.local", sampleAuthBytes(3), sampleAuthBytes(99)};
}
inline Welcome sampleWelcome() {
    return {42, 0x0123456789ABCDEFull, sampleAuthBytes(17)};
}
inline Challenge sampleChallenge() {
    return {kVersion, "0.1.0-abc123", true, sampleAuthBytes(201)};
}

/// One change of every kind, each field away from its default (names and the texture are not
/// carried, so they stay at theirs), negative where allowed.
inline std::vector<SceneChange> sampleChanges() {
    CameraChange camera;
    camera.camera.position = {0.5f, -2.25f, 7.0f};
    camera.camera.lookAt = {-1.0f, 0.125f, -3.5f};
    camera.camera.up = {0.0f, 0.0f, -1.0f};
    camera.camera.fovYDeg = 61.5f;

    TransformChange transform;
    transform.mesh = 7;
    transform.transform.translate = {1.5f, -2.0f, 1e-7f};
    transform.transform.rotateDeg = {-90.0f, 45.0f, 370.0f};
    transform.transform.scale = {2.0f, -0.5f, 1e6f};

    PunctualLightChange point;
    point.light = 3;
    point.value.position = {-4.0f, 5.5f, 0.25f};
    point.value.intensity = {100.0f, 0.0f, 3.75f};
    point.value.on = false;

    QuadLightChange quad;
    quad.light = 0xFFFFFFFFu;  // indices are the scene's business, not the protocol's
    quad.value.corner = {-0.25f, 1.98f, -0.25f};
    quad.value.edge1 = {0.5f, 0.0f, 0.0f};
    quad.value.edge2 = {0.0f, 0.0f, 0.5f};
    quad.value.radiance = {17.0f, 12.0f, 4.0f};
    quad.value.on = false;

    MaterialChange material;
    material.material = 12;
    material.value.diffuse = {0.1f, 0.2f, 0.3f};
    material.value.specular = {0.4f, 0.5f, 0.6f};
    material.value.phongExponent = 250.0f;
    material.value.reflection = Reflection::Glossy;
    material.value.glass = true;
    material.value.ior = 1.33f;
    material.value.transmittance = {0.9f, 0.8f, 0.7f};
    material.value.emission = {0.0f, 2.5f, 1.0f};

    MaterialChange mirror;
    mirror.material = 1;
    mirror.value.reflection = Reflection::Mirror;
    mirror.value.specular = {1.0f, 1.0f, 1.0f};

    EnvironmentChange environment;
    environment.value.radiance = {2.5f, 0.0f, 1e-3f};
    environment.value.rotateDeg = -400.0f;

    // The render settings: a settings command's (every field; the defaults, some changed).
    SettingsChange settings;
    settings.settings.indirectVpls = 64;
    settings.settings.directSamples = 9;
    settings.settings.lightSampling = LightSampling::Tree;
    settings.settings.clampCompensation = ClampCompensation::Shrink;
    settings.settings.progressiveAlpha = 0.5f;
    settings.settings.seed = 0xFEDCBA9876543210ull;

    return {camera, transform, point, quad, material, mirror, environment, settings};
}

inline SceneUpdate sampleSceneUpdate() {
    return {sampleChanges()};
}

inline SceneData sampleSceneData() {
    SceneData m;
    m.bundle.sceneName = "cornell.json";
    m.bundle.sceneText = R"({"camera": {"position": [0, 1, 3.5]}, "meshes": ["box.obj"]})";
    m.bundle.files["box.obj"] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    m.bundle.files["tex/wood.png"] = std::string("\x89PNG\r\n\x1a\n\0\0\0binary", 17);
    m.settings.integrator = IntegratorKind::Path;
    m.settings.interleaveX = 4;
    m.settings.interleaveY = 2;
    m.settings.directSamples = 7;
    m.settings.vplPaths = 33;
    m.settings.indirectVpls = 21;
    m.settings.maxLightPathLength = 5;
    m.settings.clampDistance = 0.03f;
    m.settings.causticPhotons = 1234;
    m.settings.causticRadius = 0.015f;
    m.settings.maxEyeDepth = 9;
    m.settings.filterX = 5;
    m.settings.filterY = 6;
    m.settings.filterDepthThreshold = 0.07f;
    m.settings.filterNormalThreshold = 0.8f;
    m.settings.accumulate = false;
    m.settings.pathSamples = 17;
    m.settings.maxPathLength = 11;
    m.settings.tileSize = 48;
    m.settings.seed = 0xFEEDFACECAFEBEEFull;
    m.settings.roulette = false;
    m.settings.rouletteMaxLength = 33;
    m.settings.clampCompensation = ClampCompensation::Shrink;
    m.settings.indirectCausticPhotons = 4321;
    m.settings.glossyBound = 2.5f;
    m.settings.indirectCausticRadius = 0.07f;
    m.settings.progressiveRadius = false;
    m.settings.progressiveFilter = false;
    m.settings.progressiveAlpha = 0.5f;
    m.settings.gi = GiMode::Stream;
    m.settings.streamVsls = 77;
    m.settings.streamPhotons = 999;
    m.settings.streamWindow = 5;
    m.settings.sptGroups = 72;
    m.settings.sptPaths = 7;
    m.settings.sptPilots = 3;
    m.settings.sptBudget = 11;
    m.settings.lightSampling = LightSampling::Tree;
    m.settings.poolCaustics = false;
    m.settings.cacheSpacing = 0.03f;
    m.settings.cacheRadius = 2.5f;
    m.settings.photonmapGroups = 128;
    m.settings.photonmapPhotons = 8;
    m.settings.photonmapNeighbours = 48;
    m.settings.photonmapGather = 32;
    m.settings.photonmapScreenCaustics = false;
    m.settings.vplSampling = VplSampling::Importance;
    m.settings.vplPool = 99;
    m.settings.lightEdgeRays = 5;
    m.settings.firstFrameDivisor = 7;
    m.image = {800, 600, -1.5f};
    m.camera.position = {1.0f, 2.0f, 3.0f};
    m.camera.lookAt = {-1.0f, 0.5f, 0.25f};
    m.camera.up = {0.0f, 0.0f, 1.0f};
    m.camera.fovYDeg = 38.5f;
    m.changes = sampleChanges();
    m.baseFirstFrame = 17;
    m.history = {{18, sampleChanges()}, {25, {}}};
    return m;
}

inline SceneReady sampleSceneReady() {
    return {290000, 1.25f};
}
inline TileAssign sampleTileAssign() {
    return {77, 96, 192, 96, 64, 2, 1, 300};
}

/// A tile with smooth reflectance, normals and depth and noisy irradiance, like a real one.
inline TileChannels sampleChannels(int n, std::uint32_t seed = 1) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    TileChannels c;
    c.resize(n, kAllChannels);
    const int w = std::max(1, static_cast<int>(std::sqrt(static_cast<float>(n))));
    for (int i = 0; i < n; ++i) {
        const float x = static_cast<float>(i % w) / w, y = static_cast<float>(i / w) / w;
        const float smooth = 0.5f + 0.3f * std::sin(3.0f * x + 2.0f * y);
        c.irradiance[i] = glm::vec3(2.0f, 1.8f, 1.5f) * smooth * (0.5f + u(rng));
        c.reflectance[i] = glm::vec3(0.7f, 0.5f, 0.3f) * (0.8f + 0.2f * x);
        c.normal[i] = glm::normalize(glm::vec3(0.2f * x - 0.1f, 1.0f, 0.1f * y));
        c.depth[i] = 3.0f + x + 0.5f * y;
        c.unfiltered[i] = (i % 17 == 0) ? glm::vec3(5.0f * u(rng)) : glm::vec3(0.0f);
        c.glossy[i] = (i % 5 == 0) ? glm::vec3(0.3f * u(rng), 0.2f, 0.1f) : glm::vec3(0.0f);
    }
    return c;
}

inline TileResult sampleTileResult(int n = 256) {
    TileResult m;
    m.tileId = 991;
    m.stats = {123456789012ull, 98765432101ull, 18, 500, 2, 0.0375f};
    m.channels = sampleChannels(n);
    return m;
}

inline Error sampleError() {
    return {"scene failed to load: box.obj line 3: bad face"};
}

inline std::vector<Message> sampleMessages() {
    return {sampleHello(),      sampleWelcome(),     sampleSceneData(), sampleSceneReady(),
            sampleTileAssign(), sampleTileResult(),  Heartbeat{},       Shutdown{},
            sampleError(),      sampleSceneUpdate(), sampleChallenge()};
}

}  // namespace igi::proto::test
