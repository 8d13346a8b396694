#include "ChangeCodec.h"

#include <gtest/gtest.h>

#include "util/ExpectContains.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <iostream>
#include <new>
#include <random>

#include "Codec.h"
#include "Compression.h"
#include "SceneCodec.h"
#include "TestMessages.h"

// ---- the largest allocation a decode makes ----
// Replacing the global allocator is the only way to see that a count is refused *before* the
// vector is reserved: a decoder that reserved first and checked afterwards would still throw,
// but it would have asked for gigabytes on the way.
namespace {
thread_local bool gTrackAllocations = false;
thread_local std::size_t gLargestAllocation = 0;
}  // namespace

// GCC sees free() called on what "new" returned once these are inlined; they pair on purpose.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t n) {
    if (gTrackAllocations && n > gLargestAllocation) gLargestAllocation = n;
    if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
    std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
    std::free(p);
}
#pragma GCC diagnostic pop

namespace igi::proto {
namespace {

using test::sampleChanges;

std::vector<std::uint8_t> encodeChange(const SceneChange& c) {
    std::vector<std::uint8_t> bytes;
    ByteWriter out(bytes);
    writeSceneChange(out, c);
    return bytes;
}

SceneChange decodeChange(const std::vector<std::uint8_t>& bytes) {
    ByteReader in(bytes, "test");
    SceneChange c = readSceneChange(in, 0);
    in.expectEnd();
    return c;
}

std::vector<std::uint8_t> updatePayload(const std::vector<SceneChange>& changes) {
    return encodePayload(SceneUpdate{changes});
}

/// Decodes a SceneUpdate payload from a buffer of exactly its size (so that an out-of-bounds
/// read is a heap overflow AddressSanitizer reports).
SceneUpdate decodeUpdate(std::span<const std::uint8_t> payload) {
    Header h;
    h.type = MessageType::SceneUpdate;
    h.payloadSize = static_cast<std::uint32_t>(payload.size());
    const std::vector<std::uint8_t> exact(payload.begin(), payload.end());
    return std::get<SceneUpdate>(decodeMessage(h, exact));
}

std::string updateError(std::span<const std::uint8_t> payload) {
    try {
        decodeUpdate(payload);
    } catch (const ProtocolError& e) {
        return e.what();
    }
    return "(no error)";
}

/// The error of the sample update after `edit` changed it (to something the encoder writes
/// as it is, such as a NaN).
std::string errorAfter(const std::function<void(std::vector<SceneChange>&)>& edit) {
    auto changes = sampleChanges();
    edit(changes);
    return updateError(updatePayload(changes));
}

/// Byte offset of change `i` in the sample update's payload.
std::size_t offsetOfChange(std::size_t i) {
    const auto changes = sampleChanges();
    return updatePayload({changes.begin(), changes.begin() + static_cast<std::ptrdiff_t>(i)})
        .size();
}

/// The error of the sample update with one byte of change `i`, at `offset` within the change,
/// set to `value` (for what the encoder cannot produce: a bad tag, bool or enum).
std::string errorWithByte(std::size_t i, std::size_t offset, std::uint8_t value) {
    auto payload = updatePayload(sampleChanges());
    payload.at(offsetOfChange(i) + offset) = value;
    return updateError(payload);
}

// Indices of the kinds in sampleChanges().
constexpr std::size_t kCamera = 0, kTransform = 1, kPoint = 2, kQuad = 3, kMaterial = 4,
                      kEnvironment = 6, kSettings = 7;

template <typename T>
T& as(std::vector<SceneChange>& changes, std::size_t i) {
    return std::get<T>(changes.at(i));
}

// ---- round trips ----

TEST(ChangeCodec, EveryKindRoundTripsWithEveryField) {
    const auto changes = sampleChanges();
    ASSERT_EQ(changes.size(), 8u);
    for (std::size_t i = 0; i < changes.size(); ++i) {
        SCOPED_TRACE("change " + std::to_string(i));
        EXPECT_TRUE(decodeChange(encodeChange(changes[i])) == changes[i]);
    }
    // And as a message, whose header carries the epoch the update makes.
    const auto bytes = encodeMessage(SceneUpdate{changes}, 17, 42);
    const Header h =
        decodeHeader(std::span<const std::uint8_t, kHeaderSize>(bytes.data(), kHeaderSize));
    EXPECT_EQ(h.type, MessageType::SceneUpdate);
    EXPECT_EQ(h.epoch, 42u);
    const auto decoded =
        std::get<SceneUpdate>(decodeMessage(h, std::span(bytes).subspan(kHeaderSize)));
    EXPECT_TRUE(decoded.changes == changes);
}

glm::vec3 randomVec3(std::mt19937& rng, float lo, float hi) {
    std::uniform_real_distribution<float> u(lo, hi);
    return {u(rng), u(rng), u(rng)};
}

/// A valid change of the given kind with every field random, so that two fields swapped by
/// the codec cannot go unnoticed (the sample's values might coincide).
SceneChange randomChange(int kind, std::mt19937& rng) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const auto index = static_cast<std::uint32_t>(rng());
    switch (kind) {
        case 0: {
            CameraChange c;
            c.camera = {randomVec3(rng, -10, 10), randomVec3(rng, -10, 10), randomVec3(rng, -1, 1),
                        1.0f + 178.0f * u(rng)};
            return c;
        }
        case 1: {
            TransformChange c{index, {}};
            c.transform = {randomVec3(rng, -100, 100), randomVec3(rng, -360, 360),
                           randomVec3(rng, 0.01f, 10)};
            if (rng() % 2) c.transform.scale.y = -c.transform.scale.y;
            return c;
        }
        case 2: {
            PunctualLightChange c{index, {}};
            c.value.position = randomVec3(rng, -10, 10);
            c.value.intensity = randomVec3(rng, 0, 100);
            c.value.on = rng() % 2;
            return c;
        }
        case 3: {
            QuadLightChange c{index, {}};
            c.value.corner = randomVec3(rng, -10, 10);
            c.value.edge1 = randomVec3(rng, -1, 1);
            c.value.edge2 = randomVec3(rng, -1, 1);
            c.value.radiance = randomVec3(rng, 0, 50);
            c.value.on = rng() % 2;
            return c;
        }
        case 5: {
            EnvironmentChange c;
            c.value.radiance = randomVec3(rng, 0, 1e4f);
            c.value.rotateDeg = 720.0f * u(rng) - 360.0f;
            return c;
        }
        default: {
            MaterialChange c{index, {}};
            c.value.diffuse = randomVec3(rng, 0, 1);
            c.value.specular = randomVec3(rng, 0, 1);
            c.value.phongExponent = 1000.0f * u(rng);
            c.value.reflection = static_cast<Reflection>(rng() % 3);
            c.value.glass = rng() % 2;
            c.value.ior = 1.0f + u(rng);
            c.value.transmittance = randomVec3(rng, 0, 1);
            c.value.emission = randomVec3(rng, 0, 20);
            return c;
        }
    }
}

TEST(ChangeCodec, RandomChangesOfEveryKindRoundTripExactly) {
    std::mt19937 rng(2002);
    std::vector<SceneChange> changes;
    for (int i = 0; i < 600; ++i) changes.push_back(randomChange(i % 6, rng));
    const auto decoded = decodeUpdate(updatePayload(changes));
    ASSERT_EQ(decoded.changes.size(), changes.size());
    for (std::size_t i = 0; i < changes.size(); ++i)
        EXPECT_TRUE(decoded.changes[i] == changes[i]) << "change " << i;
}

TEST(ChangeCodec, EmptyUpdateRoundTrips) {
    const auto payload = updatePayload({});
    EXPECT_EQ(payload.size(), 4u);
    EXPECT_TRUE(decodeUpdate(payload).changes.empty());
}

TEST(ChangeCodec, NamesAndTextureAreNotCarried) {
    // A change never renames a light or material, nor swaps a texture: applyChanges keeps the
    // state's; the wire does not spend bytes on them.
    PunctualLightChange light{2, {}};
    light.value.name = "ceiling lamp";
    MaterialChange material{5, {}};
    material.value.name = "wood";
    material.value.diffuseTexture = 3;
    EXPECT_EQ(encodeChange(light), encodeChange(PunctualLightChange{2, {}}));
    EXPECT_EQ(encodeChange(material), encodeChange(MaterialChange{5, {}}));
    const auto decoded = std::get<MaterialChange>(decodeChange(encodeChange(material)));
    EXPECT_EQ(decoded.value.name, "");
    EXPECT_EQ(decoded.value.diffuseTexture, -1);
    // Nor the environment's map: the scene's file.
    EnvironmentChange sky;
    sky.value.texture = 2;
    EXPECT_EQ(encodeChange(sky), encodeChange(EnvironmentChange{}));
    EXPECT_EQ(std::get<EnvironmentChange>(decodeChange(encodeChange(sky))).value.texture, -1);
}

// ---- layout ----

TEST(ChangeCodec, SizesOfEveryKindAreAsDocumented) {
    EXPECT_EQ(encodeChange(CameraChange{}).size(), 41u);
    EXPECT_EQ(encodeChange(TransformChange{}).size(), 41u);
    EXPECT_EQ(encodeChange(PunctualLightChange{}).size(), 55u);
    EXPECT_EQ(encodeChange(QuadLightChange{}).size(), 54u);
    EXPECT_EQ(encodeChange(MaterialChange{}).size(), 71u);
    EXPECT_EQ(encodeChange(EnvironmentChange{}).size(), 17u);
    EXPECT_EQ(encodeChange(SettingsChange{}).size(), 172u);
    EXPECT_EQ(kMinChangeBytes, 17u);
}

// A settings change is the tag, then the settings exactly as a SceneData carries them.
TEST(ChangeCodec, SettingsLayoutIsTheSceneDatasSettings) {
    const SettingsChange c = std::get<SettingsChange>(sampleChanges()[kSettings]);
    std::vector<std::uint8_t> expected = {6};
    ByteWriter out(expected);
    writeRenderSettings(out, c.settings);
    EXPECT_EQ(encodeChange(c), expected);
}

// And checked as a SceneData's are: a client never renders with settings a master would refuse.
TEST(ChangeCodec, SettingsOutOfRangeAreRefusedNamingTheField) {
    EXPECT_CONTAINS(
        errorAfter([](auto& c) { as<SettingsChange>(c, kSettings).settings.interleaveX = 0; }),
        "interleaveX");
    EXPECT_CONTAINS(errorAfter([](auto& c) {
                        as<SettingsChange>(c, kSettings).settings.progressiveAlpha = NAN;
                    }),
                    "progressiveAlpha");
    EXPECT_EQ(errorAfter([](auto&) {}), "(no error)");
}

TEST(ChangeCodec, EnvironmentLayoutIsAsDocumented) {
    EnvironmentChange c;
    c.value.radiance = {1.0f, 2.0f, 0.5f};
    c.value.rotateDeg = -90.0f;
    std::vector<std::uint8_t> expected = {5};
    for (float f : {1.0f, 2.0f, 0.5f, -90.0f}) {
        std::uint32_t bits = 0;
        std::memcpy(&bits, &f, 4);
        for (int i = 0; i < 4; ++i) expected.push_back(std::uint8_t(bits >> (8 * i)));
    }
    EXPECT_EQ(encodeChange(c), expected);
}

TEST(ChangeCodec, EnvironmentRadianceMustNotBeNegativeNorRotationInfinite) {
    EXPECT_EQ(errorAfter(
                  [](auto& c) { as<EnvironmentChange>(c, kEnvironment).value.radiance.z = -1.0f; }),
              "SceneUpdate: change 6 (environment): radiance.z is -1.000000, expected >= 0");
    EXPECT_EQ(errorAfter([](auto& c) {
                  as<EnvironmentChange>(c, kEnvironment).value.rotateDeg = INFINITY;
              }),
              "SceneUpdate: change 6 (environment): rotateDeg is inf, expected finite");
}

TEST(ChangeCodec, PunctualLightLayoutIsLittleEndianAsDocumented) {
    PunctualLightChange c{0x01020304, {}};
    c.value.kind = LightKind::Spot;
    c.value.position = {1.0f, -2.0f, 0.5f};
    c.value.direction = {0.0f, -1.0f, 0.0f};
    c.value.intensity = {0.0f, 1.0f, 2.0f};
    c.value.innerDeg = 0.0f;
    c.value.outerDeg = 2.0f;
    c.value.angleDeg = 0.5f;
    c.value.on = true;
    const std::vector<std::uint8_t> expected = {
        2,                                   // tag
        4, 3, 2,    1,                       // light index
        1,                                   // kind: spot
        0, 0, 0x80, 0x3F, 0, 0, 0,    0xC0,  // position 1, -2,
        0, 0, 0,    0x3F,                    //   0.5
        0, 0, 0,    0,    0, 0, 0x80, 0xBF,  // direction 0, -1,
        0, 0, 0,    0,                       //   0
        0, 0, 0,    0,    0, 0, 0x80, 0x3F,  // intensity 0, 1,
        0, 0, 0,    0x40,                    //   2
        0, 0, 0,    0,                       // innerDeg 0
        0, 0, 0,    0x40,                    // outerDeg 2
        0, 0, 0,    0x3F,                    // angleDeg 0.5
        1,                                   // on
    };
    EXPECT_EQ(encodeChange(c), expected);
}

TEST(ChangeCodec, MaterialFieldOrderIsAsDocumented) {
    MaterialChange c{9, {}};
    c.value.reflection = Reflection::Mirror;
    c.value.glass = true;
    c.value.ior = 2.0f;
    const auto bytes = encodeChange(c);
    // tag 0, index 1, diffuse 5, specular 17, phongExponent 29, reflection 33, glass 34,
    // ior 35, transmittance 39, emission 51.
    EXPECT_EQ(bytes.at(0), 4);
    EXPECT_EQ(bytes.at(1), 9);
    EXPECT_EQ(bytes.at(33), 2);
    EXPECT_EQ(bytes.at(34), 1);
    EXPECT_EQ(bytes.at(38), 0x40);  // high byte of 2.0f
}

// ---- truncation ----

TEST(ChangeCodec, TruncationAtEveryLengthThrows) {
    const auto payload = updatePayload(sampleChanges());
    for (std::size_t n = 0; n < payload.size(); ++n)
        EXPECT_THROW(decodeUpdate(std::span(payload).first(n)), ProtocolError)
            << "truncated to " << n << " of " << payload.size() << " bytes";
    for (const SceneChange& c : sampleChanges()) {
        const auto bytes = encodeChange(c);
        for (std::size_t n = 0; n < bytes.size(); ++n) {
            ByteReader in{std::span(bytes).first(n), "test"};
            EXPECT_THROW(readSceneChange(in, 0), ProtocolError);
        }
    }
}

TEST(ChangeCodec, TrailingBytesThrow) {
    auto payload = updatePayload(sampleChanges());
    payload.push_back(0);
    EXPECT_CONTAINS(updateError(payload), "trailing");
}

// ---- validation: every refusal names the change and the field ----

TEST(ChangeCodec, UnknownTagIsRefusedWithItsIndex) {
    EXPECT_EQ(errorWithByte(3, 0, 7), "SceneUpdate: change 3: unknown tag 7, expected 0 .. 6");
    EXPECT_CONTAINS(errorWithByte(0, 0, 255), "change 0: unknown tag 255");
    EXPECT_EQ(errorWithByte(3, 0, 3), "(no error)");  // the byte patched back to itself
}

TEST(ChangeCodec, NonFiniteFloatsAreRefusedWithIndexAndField) {
    EXPECT_EQ(errorAfter([](auto& c) { as<MaterialChange>(c, kMaterial).value.diffuse.y = NAN; }),
              "SceneUpdate: change 4 (material): diffuse.y is nan, expected finite");
    EXPECT_CONTAINS(errorAfter([](auto& c) {
                        as<TransformChange>(c, kTransform).transform.translate.z = INFINITY;
                    }),
                    "change 1 (transform): translate.z is inf");
    EXPECT_CONTAINS(
        errorAfter([](auto& c) { as<TransformChange>(c, kTransform).transform.rotateDeg.x = NAN; }),
        "change 1 (transform): rotateDeg.x");
    EXPECT_CONTAINS(
        errorAfter([](auto& c) { as<CameraChange>(c, kCamera).camera.up.z = -INFINITY; }),
        "change 0 (camera): up.z");
    EXPECT_CONTAINS(
        errorAfter([](auto& c) { as<PunctualLightChange>(c, kPoint).value.position.x = NAN; }),
        "change 2 (punctual light): position.x");
    EXPECT_CONTAINS(
        errorAfter([](auto& c) { as<QuadLightChange>(c, kQuad).value.edge2.y = INFINITY; }),
        "change 3 (quad light): edge2.y");
    EXPECT_CONTAINS(
        errorAfter([](auto& c) { as<MaterialChange>(c, kMaterial).value.phongExponent = NAN; }),
        "change 4 (material): phongExponent");
    EXPECT_CONTAINS(
        errorAfter([](auto& c) { as<MaterialChange>(c, kMaterial).value.ior = INFINITY; }),
        "change 4 (material): ior is inf");
}

TEST(ChangeCodec, BadBooleansAreRefusedWithIndexAndField) {
    // Offsets within the change: punctual light `on` 54, quad light `on` 53, material `glass` 34.
    EXPECT_EQ(errorWithByte(kPoint, 54, 2),
              "SceneUpdate: change 2 (punctual light): on is 2, expected 0 or 1");
    EXPECT_CONTAINS(errorWithByte(kQuad, 53, 0xFF), "change 3 (quad light): on is 255");
    EXPECT_CONTAINS(errorWithByte(kMaterial, 34, 7), "change 4 (material): glass is 7");
    EXPECT_EQ(errorWithByte(kPoint, 54, 1), "(no error)");
}

TEST(ChangeCodec, RoughnessAndMetallicMustBeFractions) {
    EXPECT_CONTAINS(errorAfter([](auto& c) { as<MaterialChange>(c, 5).value.roughness = 1.5f; }),
                    "change 5 (material): roughness is 1.500000, expected in [0, 1]");
    EXPECT_CONTAINS(errorAfter([](auto& c) { as<MaterialChange>(c, 5).value.metallic = -0.25f; }),
                    "change 5 (material): metallic is -0.250000, expected in [0, 1]");
}

TEST(ChangeCodec, UnknownReflectionIsRefusedWithIndex) {
    EXPECT_EQ(errorWithByte(kMaterial, 33, 3), "(no error)");  // 3 is GGX
    EXPECT_CONTAINS(errorWithByte(kMaterial, 33, 4), "change 4 (material): reflection is 4");
    EXPECT_CONTAINS(errorAfter([](auto& c) {
                        as<MaterialChange>(c, 5).value.reflection = static_cast<Reflection>(200);
                    }),
                    "change 5 (material): reflection is 200");
    EXPECT_EQ(errorWithByte(kMaterial, 33, 2), "(no error)");
}

TEST(ChangeCodec, CameraMustBeUsable) {
    for (float fov : {0.0f, -10.0f, 180.0f, 200.0f}) {
        EXPECT_CONTAINS(
            errorAfter([&](auto& c) { as<CameraChange>(c, kCamera).camera.fovYDeg = fov; }),
            "change 0 (camera): fovYDeg is");
    }
    EXPECT_CONTAINS(errorAfter([](auto& c) { as<CameraChange>(c, kCamera).camera.fovYDeg = NAN; }),
                    "change 0 (camera): fovYDeg is nan");
    EXPECT_CONTAINS(errorAfter([](auto& c) {
                        auto& cam = as<CameraChange>(c, kCamera).camera;
                        cam.lookAt = cam.position;
                    }),
                    "change 0 (camera): position equals lookAt");
    EXPECT_EQ(errorAfter([](auto& c) { as<CameraChange>(c, kCamera).camera.fovYDeg = 179.5f; }),
              "(no error)");
}

TEST(ChangeCodec, ScaleComponentsMustBeNonZero) {
    EXPECT_EQ(
        errorAfter([](auto& c) { as<TransformChange>(c, kTransform).transform.scale.y = 0.0f; }),
        "SceneUpdate: change 1 (transform): scale.y is 0, expected non-zero");
    EXPECT_CONTAINS(
        errorAfter([](auto& c) { as<TransformChange>(c, kTransform).transform.scale.z = -0.0f; }),
        "scale.z is 0");
    // A negative scale mirrors the object: allowed (the sample has one).
    EXPECT_LT(std::get<TransformChange>(sampleChanges()[kTransform]).transform.scale.y, 0.0f);
}

TEST(ChangeCodec, IorMustBePositive) {
    for (float ior : {0.0f, -1.0f}) {
        EXPECT_CONTAINS(
            errorAfter([&](auto& c) { as<MaterialChange>(c, kMaterial).value.ior = ior; }),
            "change 4 (material): ior is");
    }
    EXPECT_EQ(errorAfter([](auto& c) { as<MaterialChange>(c, kMaterial).value.ior = 0.5f; }),
              "(no error)");
}

TEST(ChangeCodec, ColoursAndPhongExponentMustNotBeNegative) {
    EXPECT_EQ(
        errorAfter([](auto& c) { as<PunctualLightChange>(c, kPoint).value.intensity.z = -1.0f; }),
        "SceneUpdate: change 2 (punctual light): intensity.z is -1.000000, expected >= 0");
    EXPECT_CONTAINS(
        errorAfter([](auto& c) { as<QuadLightChange>(c, kQuad).value.radiance.x = -0.5f; }),
        "change 3 (quad light): radiance.x");
    using M = MaterialChange;
    EXPECT_CONTAINS(errorAfter([](auto& c) { as<M>(c, kMaterial).value.diffuse.x = -0.1f; }),
                    "change 4 (material): diffuse.x");
    EXPECT_CONTAINS(errorAfter([](auto& c) { as<M>(c, kMaterial).value.specular.y = -0.1f; }),
                    "change 4 (material): specular.y");
    EXPECT_CONTAINS(errorAfter([](auto& c) { as<M>(c, kMaterial).value.transmittance.z = -1; }),
                    "change 4 (material): transmittance.z");
    EXPECT_CONTAINS(errorAfter([](auto& c) { as<M>(c, kMaterial).value.emission.x = -2; }),
                    "change 4 (material): emission.x");
    EXPECT_CONTAINS(errorAfter([](auto& c) { as<M>(c, kMaterial).value.phongExponent = -1; }),
                    "change 4 (material): phongExponent");
    // Zero is a colour (black), and a light may be off.
    EXPECT_EQ(errorAfter([](auto& c) { as<M>(c, kMaterial).value.diffuse = glm::vec3(0.0f); }),
              "(no error)");
}

TEST(ChangeCodec, IndicesAreNotCheckedByTheProtocol) {
    // The protocol does not know the scene; applyChanges refuses an index out of range.
    auto changes = sampleChanges();
    as<TransformChange>(changes, kTransform).mesh = 0xFFFFFFFFu;
    EXPECT_TRUE(decodeUpdate(updatePayload(changes)).changes == changes);
}

// ---- counts and limits ----

std::vector<std::uint8_t> payloadClaiming(std::uint32_t count, std::size_t bytesAfter) {
    std::vector<std::uint8_t> payload;
    ByteWriter out(payload);
    out.u32(count);
    for (std::size_t i = 0; i < bytesAfter; ++i) out.u8(0);  // camera tags, zero fields
    return payload;
}

/// The error of decoding `payload`, and the largest allocation made meanwhile.
std::pair<std::string, std::size_t> errorAndLargestAllocation(
    const std::vector<std::uint8_t>& payload) {
    Header h;
    h.type = MessageType::SceneUpdate;
    h.payloadSize = static_cast<std::uint32_t>(payload.size());
    std::string error = "(no error)";
    gLargestAllocation = 0;
    gTrackAllocations = true;
    try {
        decodeMessage(h, payload);
    } catch (const ProtocolError& e) {
        error = e.what();
    } catch (const std::exception& e) {
        error = std::string("unexpected ") + e.what();
    }
    gTrackAllocations = false;
    return {error, gLargestAllocation};
}

TEST(ChangeCodec, CountBeyondTheLimitIsRefusedBeforeAllocating) {
    // Reserving 2^31 changes would ask for over 200 GB.
    const auto [error, largest] = errorAndLargestAllocation(payloadClaiming(1u << 31, 64));
    EXPECT_EQ(error, "SceneUpdate: 2147483648 scene changes exceed the limit of 1000000");
    EXPECT_LT(largest, 4096u);
}

TEST(ChangeCodec, CountBeyondTheBytesIsRefusedBeforeAllocating) {
    // Within the limit, but a million changes cannot fit in 100 bytes: 112 MB are not reserved.
    const auto [error, largest] = errorAndLargestAllocation(payloadClaiming(kMaxSceneChanges, 100));
    EXPECT_EQ(error, "SceneUpdate: 1000000 scene changes cannot fit in the 100 bytes left");
    EXPECT_LT(largest, 4096u);
    // Three changes need at least 51 bytes.
    EXPECT_CONTAINS(errorAndLargestAllocation(payloadClaiming(3, 50)).first, "cannot fit");
}

TEST(ChangeCodec, SceneDataChangeCountIsCheckedToo) {
    std::vector<std::uint8_t> body;
    ByteWriter out(body);
    writeSceneBundle(out, SceneBundle{});
    writeRenderSettings(out, RenderSettings{});
    writeImageSettings(out, ImageSettings{});
    writeCamera(out, Camera{});
    out.u32(1u << 31);
    std::vector<std::uint8_t> payload;
    ByteWriter p(payload);
    p.u64(body.size());
    zstdCompressAppend(body, 3, payload);
    Header h;
    h.type = MessageType::SceneData;
    h.payloadSize = static_cast<std::uint32_t>(payload.size());
    std::string error = "(no error)";
    try {
        decodeMessage(h, payload);
    } catch (const ProtocolError& e) {
        error = e.what();
    }
    EXPECT_EQ(error, "SceneData body: 2147483648 scene changes exceed the limit of 1000000");
}

TEST(ChangeCodec, EncoderRefusesAnUpdateOverSixteenMebibytes) {
    // 71-byte material changes: one more than fits in 16 MiB.
    const std::size_t fits = ((16u << 20) - 4) / 71;
    std::vector<SceneChange> changes(fits, MaterialChange{});
    EXPECT_LE(encodePayload(SceneUpdate{changes}).size(), 16u << 20);
    changes.push_back(MaterialChange{});
    EXPECT_THROW(encodePayload(SceneUpdate{changes}), ProtocolError);
}

// ---- fuzzing ----

/// Anything but success or ProtocolError is a failure; returns whether it decoded.
bool decodeMustNotCrash(std::span<const std::uint8_t> payload) {
    try {
        decodeUpdate(payload);
        return true;
    } catch (const ProtocolError&) {
    } catch (const std::exception& e) {
        ADD_FAILURE() << "unexpected " << typeid(e).name() << ": " << e.what();
    }
    return false;
}

TEST(ChangeCodec, FuzzedUpdatesThrowOrDecode) {
    std::mt19937 rng(1002);
    std::uniform_int_distribution<int> byte(0, 255);
    const auto valid = updatePayload(sampleChanges());
    int decoded = 0;
    for (int i = 0; i < 20000; ++i) {
        auto p = valid;
        const int flips = 1 + static_cast<int>(rng() % 6);
        for (int f = 0; f < flips; ++f) p[rng() % p.size()] = static_cast<std::uint8_t>(byte(rng));
        if (rng() % 4 == 0) p.resize(rng() % (p.size() + 1));
        decoded += decodeMustNotCrash(p);
    }
    std::cout << "fuzz SceneUpdate (mutated): " << decoded << " of 20000 decoded\n";
    EXPECT_GT(decoded, 0);  // some flips land on harmless bits: the fuzzing reaches the end
}

TEST(ChangeCodec, RandomUpdatesThrowOrDecode) {
    // Shaped like updates (a small count, then tags mostly valid, then random field bytes of
    // the right length), so that the field checks, not the first length check, are exercised.
    std::mt19937 rng(1003);
    std::uniform_int_distribution<int> byte(0, 255);
    constexpr std::size_t kFieldBytes[] = {40, 40, 54, 53, 70, 16};
    int decoded = 0;
    for (int i = 0; i < 20000; ++i) {
        std::vector<std::uint8_t> p;
        ByteWriter out(p);
        const std::uint32_t count = rng() % 4;
        out.u32(count);
        for (std::uint32_t c = 0; c < count; ++c) {
            const std::uint8_t tag = static_cast<std::uint8_t>(rng() % 7);
            out.u8(tag);
            const std::size_t n = tag < 6 ? kFieldBytes[tag] : rng() % 64;
            for (std::size_t b = 0; b < n; ++b) {
                // Mostly bytes of small, finite, positive floats and of valid booleans.
                out.u8(static_cast<std::uint8_t>(rng() % 3 ? rng() % 2 : byte(rng)));
            }
        }
        if (rng() % 8 == 0) p.resize(rng() % (p.size() + 1));
        decoded += decodeMustNotCrash(p);
    }
    std::cout << "fuzz SceneUpdate (random): " << decoded << " of 20000 decoded\n";
    EXPECT_GT(decoded, 0);
}

}  // namespace
}  // namespace igi::proto
