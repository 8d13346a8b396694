#include "SceneCodec.h"

#include "ChangeCodec.h"

#include <cmath>
#include <string>

namespace igi::proto {
namespace {

// A new field in one of these structs must be added to the codec and to docs/PROTOCOL.md, or
// it silently never reaches the clients. These sizes make the compiler say so (x86-64 / LP64).
static_assert(sizeof(RenderSettings) == 192, "RenderSettings changed: update SceneCodec.cpp");
static_assert(sizeof(ImageSettings) == 12, "ImageSettings changed: update SceneCodec.cpp");
static_assert(sizeof(Camera) == 40, "Camera changed: update SceneCodec.cpp");
static_assert(sizeof(SceneBundle) == 2 * sizeof(std::string) + sizeof(SceneBundle::files),
              "SceneBundle changed: update SceneCodec.cpp");

int readInt(ByteReader& in, const char* name, int lo, int hi) {
    const std::int32_t v = in.i32();
    if (v < lo || v > hi)
        in.fail(std::string(name) + " is " + std::to_string(v) + ", expected " +
                std::to_string(lo) + " .. " + std::to_string(hi));
    return v;
}

float readFloat(ByteReader& in, const char* name, float lo, float hi) {
    const float v = in.f32();
    if (!(v >= lo && v <= hi))  // also refuses NaN
        in.fail(std::string(name) + " is " + std::to_string(v) + ", expected " +
                std::to_string(lo) + " .. " + std::to_string(hi));
    return v;
}

float readFinite(ByteReader& in, const char* name) {
    const float v = in.f32();
    if (!std::isfinite(v)) in.fail(std::string(name) + " is not finite");
    return v;
}

glm::vec3 readVec3(ByteReader& in, const char* name) {
    glm::vec3 v;
    for (int i = 0; i < 3; ++i) v[i] = readFinite(in, name);
    return v;
}

void writeVec3(ByteWriter& out, glm::vec3 v) {
    for (int i = 0; i < 3; ++i) out.f32(v[i]);
}

constexpr int kMi = 1 << 20;  // 1,048,576

}  // namespace

void writeRenderSettings(ByteWriter& out, const RenderSettings& s) {
    out.u8(static_cast<std::uint8_t>(s.integrator));
    out.i32(s.interleaveX);
    out.i32(s.interleaveY);
    out.i32(s.directSamples);
    out.i32(s.vplPaths);
    out.i32(s.indirectVpls);
    out.i32(s.maxLightPathLength);
    out.f32(s.clampDistance);
    out.i32(s.causticPhotons);
    out.f32(s.causticRadius);
    out.i32(s.maxEyeDepth);
    out.i32(s.filterX);
    out.i32(s.filterY);
    out.f32(s.filterDepthThreshold);
    out.f32(s.filterNormalThreshold);
    out.boolean(s.accumulate);
    out.i32(s.pathSamples);
    out.i32(s.maxPathLength);
    out.i32(s.tileSize);
    out.u64(s.seed);
    out.boolean(s.roulette);
    out.i32(s.rouletteMaxLength);
    out.u8(static_cast<std::uint8_t>(s.clampCompensation));
    out.i32(s.indirectCausticPhotons);
    out.f32(s.indirectCausticRadius);
    out.f32(s.glossyBound);
    out.boolean(s.progressiveRadius);
    out.boolean(s.progressiveFilter);
    out.f32(s.progressiveAlpha);
    out.u8(static_cast<std::uint8_t>(s.gi));
    out.i32(s.streamVsls);
    out.i32(s.streamPhotons);
    out.i32(s.streamWindow);
    out.i32(s.sptGroups);
    out.i32(s.sptPaths);
    out.i32(s.sptPilots);
    out.i32(s.sptBudget);
    out.u8(static_cast<std::uint8_t>(s.lightSampling));
    out.boolean(s.poolCaustics);
    out.f32(s.cacheSpacing);
    out.f32(s.cacheRadius);
    out.i32(s.photonmapGroups);
    out.i32(s.photonmapPhotons);
    out.i32(s.photonmapNeighbours);
    out.i32(s.photonmapGather);
    out.boolean(s.photonmapScreenCaustics);
    out.u8(static_cast<std::uint8_t>(s.vplSampling));
    out.i32(s.vplPool);
    out.i32(s.lightEdgeRays);
    out.i32(s.firstFrameDivisor);
}

RenderSettings readRenderSettings(ByteReader& in) {
    RenderSettings s;
    const std::uint8_t integrator = in.u8();
    if (integrator > static_cast<std::uint8_t>(IntegratorKind::Path))
        in.fail("unknown integrator kind " + std::to_string(integrator));
    s.integrator = static_cast<IntegratorKind>(integrator);
    s.interleaveX = readInt(in, "interleaveX", 1, 16);
    s.interleaveY = readInt(in, "interleaveY", 1, 16);
    s.directSamples = readInt(in, "directSamples", 0, 4096);
    s.vplPaths = readInt(in, "vplPaths", 0, kMi);
    s.indirectVpls = readInt(in, "indirectVpls", 0, kMi);
    s.maxLightPathLength = readInt(in, "maxLightPathLength", 1, 64);
    s.clampDistance = readFloat(in, "clampDistance", 0.0f, 1.0f);
    s.causticPhotons = readInt(in, "causticPhotons", 0, 16 * kMi);
    s.causticRadius = readFloat(in, "causticRadius", 0.0f, 1.0f);
    s.maxEyeDepth = readInt(in, "maxEyeDepth", 0, 256);
    s.filterX = readInt(in, "filterX", 0, 64);
    s.filterY = readInt(in, "filterY", 0, 64);
    s.filterDepthThreshold = readFloat(in, "filterDepthThreshold", 0.0f, 1e30f);
    s.filterNormalThreshold = readFloat(in, "filterNormalThreshold", -1.0f, 1.0f);
    s.accumulate = in.boolean();
    s.pathSamples = readInt(in, "pathSamples", 1, 1 << 16);
    s.maxPathLength = readInt(in, "maxPathLength", 1, 1024);
    s.tileSize = readInt(in, "tileSize", 1, 1024);
    s.seed = in.u64();
    s.roulette = in.boolean();
    s.rouletteMaxLength = readInt(in, "rouletteMaxLength", 2, 1024);
    const std::uint8_t compensation = in.u8();
    if (compensation > static_cast<std::uint8_t>(ClampCompensation::KolligKeller))
        in.fail("unknown clamp compensation " + std::to_string(compensation));
    s.clampCompensation = static_cast<ClampCompensation>(compensation);
    s.indirectCausticPhotons = readInt(in, "indirectCausticPhotons", 0, 16 * kMi);
    s.indirectCausticRadius = readFloat(in, "indirectCausticRadius", 0.0f, 1.0f);
    s.glossyBound = readFloat(in, "glossyBound", 1.0f, 1e6f);
    s.progressiveRadius = in.boolean();
    s.progressiveFilter = in.boolean();
    s.progressiveAlpha = readFloat(in, "progressiveAlpha", 1e-3f, 0.999f);
    const std::uint8_t gi = in.u8();
    if (gi > static_cast<std::uint8_t>(GiMode::PhotonMap))
        in.fail("unknown GI mode " + std::to_string(gi));
    s.gi = static_cast<GiMode>(gi);
    s.streamVsls = readInt(in, "streamVsls", 1, kMaxStreamVsls);
    s.streamPhotons = readInt(in, "streamPhotons", 1, 16 * kMi);
    s.streamWindow = readInt(in, "streamWindow", 1, kMaxStreamWindow);
    s.sptGroups = readInt(in, "sptGroups", 1, kMaxSptGroups);
    s.sptPaths = readInt(in, "sptPaths", 1, 1024);
    s.sptPilots = readInt(in, "sptPilots", 1, s.sptPaths);
    s.sptBudget = readInt(in, "sptBudget", 1, kMaxSptGroups);
    const std::uint8_t lightSampling = in.u8();
    if (lightSampling > static_cast<std::uint8_t>(LightSampling::Tree))
        in.fail("unknown light sampling " + std::to_string(lightSampling));
    s.lightSampling = static_cast<LightSampling>(lightSampling);
    s.poolCaustics = in.boolean();
    s.cacheSpacing = readFloat(in, "cacheSpacing", 1e-6f, 0.999f);
    s.cacheRadius = readFloat(in, "cacheRadius", 0.5f, 16.0f);
    s.photonmapGroups = readInt(in, "photonmapGroups", 1, kMaxPhotonmapGroups);
    s.photonmapPhotons =
        readInt(in, "photonmapPhotons", 1, maxPhotonmapPhotonsPerGroup(s.photonmapGroups));
    s.photonmapNeighbours = readInt(in, "photonmapNeighbours", 1, 4096);
    s.photonmapGather = readInt(in, "photonmapGather", 1, 65536);
    s.photonmapScreenCaustics = in.boolean();
    const std::uint8_t vplSampling = in.u8();
    if (vplSampling > static_cast<std::uint8_t>(VplSampling::Importance))
        in.fail("unknown VPL sampling " + std::to_string(vplSampling));
    s.vplSampling = static_cast<VplSampling>(vplSampling);
    s.vplPool = readInt(in, "vplPool", 0, 100000);
    s.lightEdgeRays = readInt(in, "lightEdgeRays", 0, 1024);
    s.firstFrameDivisor = readInt(in, "firstFrameDivisor", 0, kMaxFirstFrameDivisor);
    return s;
}

void writeImageSettings(ByteWriter& out, const ImageSettings& s) {
    out.i32(s.width);
    out.i32(s.height);
    out.f32(s.exposure);
}

ImageSettings readImageSettings(ByteReader& in) {
    ImageSettings s;
    s.width = readInt(in, "image width", 1, 65535);  // tile coordinates are u16
    s.height = readInt(in, "image height", 1, 65535);
    s.exposure = readFloat(in, "exposure", -100.0f, 100.0f);
    return s;
}

void writeSceneHistory(ByteWriter& out, std::uint32_t baseFirstFrame,
                       const std::vector<EpochChanges>& history) {
    if (history.size() > kMaxHistoryEpochs)
        throw ProtocolError(std::to_string(history.size()) +
                            " epochs of history exceed the limit of " +
                            std::to_string(kMaxHistoryEpochs));
    out.u32(baseFirstFrame);
    out.u32(std::uint32_t(history.size()));
    for (const EpochChanges& e : history) {
        out.u32(e.firstFrame);
        writeSceneChanges(out, e.changes);
    }
}

std::vector<EpochChanges> readSceneHistory(ByteReader& in, std::uint32_t& baseFirstFrame) {
    baseFirstFrame = in.u32();
    const std::uint32_t count = in.u32();
    if (count > kMaxHistoryEpochs)
        in.fail(std::to_string(count) + " epochs of history exceed the limit of " +
                std::to_string(kMaxHistoryEpochs));
    // Each epoch takes at least its frame and its change count.
    if (std::uint64_t(count) * 8 > in.remaining())
        in.fail(std::to_string(count) + " epochs of history cannot fit in the " +
                std::to_string(in.remaining()) + " bytes left");
    std::vector<EpochChanges> history(count);
    std::uint32_t previous = baseFirstFrame;
    for (EpochChanges& e : history) {
        e.firstFrame = in.u32();
        if (e.firstFrame <= previous)
            in.fail("history epoch begins at frame " + std::to_string(e.firstFrame) +
                    ", not after " + std::to_string(previous));
        previous = e.firstFrame;
        e.changes = readSceneChanges(in);
    }
    return history;
}

void writeCamera(ByteWriter& out, const Camera& c) {
    writeVec3(out, c.position);
    writeVec3(out, c.lookAt);
    writeVec3(out, c.up);
    out.f32(c.fovYDeg);
}

Camera readCamera(ByteReader& in) {
    Camera c;
    c.position = readVec3(in, "camera position");
    c.lookAt = readVec3(in, "camera lookAt");
    c.up = readVec3(in, "camera up");
    c.fovYDeg = in.f32();
    if (!(c.fovYDeg > 0.0f && c.fovYDeg < 180.0f))
        in.fail("camera fovYDeg is " + std::to_string(c.fovYDeg) + ", expected 0 < fov < 180");
    return c;
}

void writeSceneBundle(ByteWriter& out, const SceneBundle& b) {
    out.string(b.sceneName);
    out.string(b.sceneText);
    out.u32(static_cast<std::uint32_t>(b.files.size()));
    for (const auto& [path, bytes] : b.files) {
        out.string(path);
        out.string(bytes);
    }
}

SceneBundle readSceneBundle(ByteReader& in) {
    SceneBundle b;
    b.sceneName = in.string();
    b.sceneText = in.string();
    const std::uint32_t files = in.u32();
    // Each file takes at least its two u32 lengths: a count beyond that is a lie.
    if (files > in.remaining() / 8)
        in.fail(std::to_string(files) + " files cannot fit in the " +
                std::to_string(in.remaining()) + " bytes left");
    for (std::uint32_t i = 0; i < files; ++i) {
        std::string path = in.string();
        if (path.empty()) in.fail("file " + std::to_string(i) + " has an empty path");
        std::string bytes = in.string();
        if (!b.files.emplace(path, std::move(bytes)).second)
            in.fail("file \"" + path + "\" appears twice");
    }
    return b;
}

}  // namespace igi::proto
