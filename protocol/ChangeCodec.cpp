#include "ChangeCodec.h"

#include <cmath>
#include <string>
#include <type_traits>

#include <glm/geometric.hpp>

#include "SceneCodec.h"

namespace igi::proto {
namespace {

// A new field in one of these structs must be added to the codec and to docs/PROTOCOL.md, or
// a client silently keeps the old value. These sizes make the compiler say so (x86-64 / LP64).
static_assert(sizeof(Camera) == 40, "Camera changed: update ChangeCodec.cpp");
static_assert(sizeof(Transform) == 36, "Transform changed: update ChangeCodec.cpp");
static_assert(sizeof(PunctualLight) == sizeof(std::string) + 56,
              "PunctualLight changed: update ChangeCodec.cpp");
static_assert(sizeof(QuadLight) == sizeof(std::string) + 56,
              "QuadLight changed: update ChangeCodec.cpp");
// Not carried: textures (emissive and bump maps too), the normal map's scale, the bump map's,
// coverage (alphaMode, alpha, alphaCutoff, alphaTexture) and the textures' uv transforms:
// applyChanges keeps the receiver's (docs/PROTOCOL.md).
static_assert(sizeof(Material) == sizeof(std::string) + 256,
              "Material changed: update ChangeCodec.cpp");
// Not carried: the environment's map (texture), the scene's file.
static_assert(sizeof(Environment) == 20, "Environment changed: update ChangeCodec.cpp");
static_assert(std::variant_size_v<SceneChange> == 7,
              "a new kind of SceneChange needs a tag in ChangeCodec.cpp");

// ---- writing ----

void writeVec3(ByteWriter& out, glm::vec3 v) {
    for (int i = 0; i < 3; ++i) out.f32(v[i]);
}

void writeTag(ByteWriter& out, ChangeTag tag) {
    out.u8(static_cast<std::uint8_t>(tag));
}

void write(ByteWriter& out, const CameraChange& c) {
    writeTag(out, ChangeTag::Camera);
    writeVec3(out, c.camera.position);
    writeVec3(out, c.camera.lookAt);
    writeVec3(out, c.camera.up);
    out.f32(c.camera.fovYDeg);
}

void write(ByteWriter& out, const TransformChange& c) {
    writeTag(out, ChangeTag::Transform);
    out.u32(c.mesh);
    writeVec3(out, c.transform.translate);
    writeVec3(out, c.transform.rotateDeg);
    writeVec3(out, c.transform.scale);
}

void write(ByteWriter& out, const PunctualLightChange& c) {
    writeTag(out, ChangeTag::PunctualLight);
    out.u32(c.light);
    out.u8(static_cast<std::uint8_t>(c.value.kind));
    writeVec3(out, c.value.position);
    writeVec3(out, c.value.direction);
    writeVec3(out, c.value.intensity);
    out.f32(c.value.innerDeg);
    out.f32(c.value.outerDeg);
    out.f32(c.value.angleDeg);
    out.boolean(c.value.on);
}

void write(ByteWriter& out, const QuadLightChange& c) {
    writeTag(out, ChangeTag::QuadLight);
    out.u32(c.light);
    writeVec3(out, c.value.corner);
    writeVec3(out, c.value.edge1);
    writeVec3(out, c.value.edge2);
    writeVec3(out, c.value.radiance);
    out.boolean(c.value.on);
}

void write(ByteWriter& out, const MaterialChange& c) {
    writeTag(out, ChangeTag::Material);
    out.u32(c.material);
    writeVec3(out, c.value.diffuse);
    writeVec3(out, c.value.specular);
    out.f32(c.value.phongExponent);
    out.u8(static_cast<std::uint8_t>(c.value.reflection));
    out.boolean(c.value.glass);
    out.f32(c.value.ior);
    writeVec3(out, c.value.transmittance);
    writeVec3(out, c.value.emission);
    out.f32(c.value.roughness);
    out.f32(c.value.metallic);
}

void write(ByteWriter& out, const EnvironmentChange& c) {
    writeTag(out, ChangeTag::Environment);
    writeVec3(out, c.value.radiance);
    out.f32(c.value.rotateDeg);
}

// Every setting, as a SceneData carries them: the receiver's checks are the same.
void write(ByteWriter& out, const SettingsChange& c) {
    writeTag(out, ChangeTag::Settings);
    writeRenderSettings(out, c.settings);
}

// ---- reading ----

/// Reads the fields of one change; every error names the change's number, its kind and the
/// field ("change 3 (material): ior is -1, expected > 0"), so a refused update can be traced
/// to what the master sent.
class ChangeFields {
  public:
    ChangeFields(ByteReader& in, std::uint32_t index, const char* kind)
        : in_(in), where_("change " + std::to_string(index) + " (" + kind + "): ") {}

    std::uint32_t index() { return in_.u32(); }

    float finite(const std::string& field) {
        const float v = in_.f32();
        if (!std::isfinite(v)) fail(field + " is " + std::to_string(v) + ", expected finite");
        return v;
    }

    float positive(const std::string& field) {
        const float v = finite(field);
        if (!(v > 0.0f)) fail(field + " is " + std::to_string(v) + ", expected > 0");
        return v;
    }

    float fraction(const std::string& field) {
        const float v = finite(field);
        if (!(v >= 0.0f && v <= 1.0f))
            fail(field + " is " + std::to_string(v) + ", expected in [0, 1]");
        return v;
    }

    float nonNegative(const std::string& field) {
        const float v = finite(field);
        if (!(v >= 0.0f)) fail(field + " is " + std::to_string(v) + ", expected >= 0");
        return v;
    }

    glm::vec3 vec3(const std::string& field) {
        glm::vec3 v(0.0f);
        for (int i = 0; i < 3; ++i) v[i] = finite(component(field, i));
        return v;
    }

    /// Radiance, intensity, albedo: a negative component would subtract light.
    glm::vec3 colour(const std::string& field) {
        glm::vec3 v(0.0f);
        for (int i = 0; i < 3; ++i) v[i] = nonNegative(component(field, i));
        return v;
    }

    /// A zero scale collapses the object to a plane (and its normals to NaN); negative mirrors.
    glm::vec3 scale(const std::string& field) {
        glm::vec3 v(0.0f);
        for (int i = 0; i < 3; ++i) {
            v[i] = finite(component(field, i));
            if (v[i] == 0.0f) fail(component(field, i) + " is 0, expected non-zero");
        }
        return v;
    }

    bool flag(const std::string& field) {
        const std::uint8_t v = in_.u8();
        if (v > 1) fail(field + " is " + std::to_string(v) + ", expected 0 or 1");
        return v == 1;
    }

    /// A unit vector: a light's direction (the master sends it normalized).
    glm::vec3 direction(const std::string& field) {
        const glm::vec3 v = vec3(field);
        const float length = glm::length(v);
        if (!(std::abs(length - 1.0f) < 1e-3f))
            fail(field + " has length " + std::to_string(length) + ", expected 1");
        return v;
    }

    LightKind lightKind() {
        const std::uint8_t v = in_.u8();
        if (v > static_cast<std::uint8_t>(LightKind::Directional))
            fail("kind is " + std::to_string(v) + ", expected 0 (point), 1 (spot) or " +
                 "2 (directional)");
        return static_cast<LightKind>(v);
    }

    Reflection reflection() {
        const std::uint8_t v = in_.u8();
        if (v > static_cast<std::uint8_t>(Reflection::Ggx))
            fail("reflection is " + std::to_string(v) + ", expected 0 (none), 1 (glossy), " +
                 "2 (mirror) or 3 (ggx)");
        return static_cast<Reflection>(v);
    }

    [[noreturn]] void fail(const std::string& message) const { in_.fail(where_ + message); }

  private:
    static std::string component(const std::string& field, int i) { return field + "." + "xyz"[i]; }

    ByteReader& in_;
    std::string where_;
};

CameraChange readCameraChange(ChangeFields& f) {
    CameraChange c;
    c.camera.position = f.vec3("position");
    c.camera.lookAt = f.vec3("lookAt");
    c.camera.up = f.vec3("up");
    c.camera.fovYDeg = f.finite("fovYDeg");
    if (!(c.camera.fovYDeg > 0.0f && c.camera.fovYDeg < 180.0f))
        f.fail("fovYDeg is " + std::to_string(c.camera.fovYDeg) + ", expected 0 < fov < 180");
    if (c.camera.position == c.camera.lookAt)
        f.fail("position equals lookAt: the camera has no view direction");
    return c;
}

TransformChange readTransformChange(ChangeFields& f) {
    TransformChange c;
    c.mesh = f.index();
    c.transform.translate = f.vec3("translate");
    c.transform.rotateDeg = f.vec3("rotateDeg");
    c.transform.scale = f.scale("scale");
    return c;
}

PunctualLightChange readPunctualLightChange(ChangeFields& f) {
    PunctualLightChange c;
    c.light = f.index();
    c.value.kind = f.lightKind();
    c.value.position = f.vec3("position");
    c.value.direction = f.direction("direction");
    c.value.intensity = f.colour("intensity");
    c.value.innerDeg = f.finite("innerDeg");
    c.value.outerDeg = f.finite("outerDeg");
    if (!(c.value.outerDeg > 0.0f && c.value.outerDeg <= 90.0f))
        f.fail("outerDeg is " + std::to_string(c.value.outerDeg) + ", expected in (0, 90]");
    if (!(c.value.innerDeg >= 0.0f && c.value.innerDeg <= c.value.outerDeg))
        f.fail("innerDeg is " + std::to_string(c.value.innerDeg) + ", expected in [0, outerDeg]");
    c.value.angleDeg = f.finite("angleDeg");
    if (!(c.value.angleDeg >= 0.0f && c.value.angleDeg <= kMaxSunAngleDeg))
        f.fail("angleDeg is " + std::to_string(c.value.angleDeg) + ", expected in [0, " +
               std::to_string(kMaxSunAngleDeg) + "]");
    c.value.on = f.flag("on");
    return c;
}

QuadLightChange readQuadLightChange(ChangeFields& f) {
    QuadLightChange c;
    c.light = f.index();
    c.value.corner = f.vec3("corner");
    c.value.edge1 = f.vec3("edge1");
    c.value.edge2 = f.vec3("edge2");
    c.value.radiance = f.colour("radiance");
    c.value.on = f.flag("on");
    return c;
}

MaterialChange readMaterialChange(ChangeFields& f) {
    MaterialChange c;
    c.material = f.index();
    c.value.diffuse = f.colour("diffuse");
    c.value.specular = f.colour("specular");
    c.value.phongExponent = f.nonNegative("phongExponent");
    c.value.reflection = f.reflection();
    c.value.glass = f.flag("glass");
    c.value.ior = f.positive("ior");
    c.value.transmittance = f.colour("transmittance");
    c.value.emission = f.colour("emission");
    c.value.roughness = f.fraction("roughness");
    c.value.metallic = f.fraction("metallic");
    return c;
}

EnvironmentChange readEnvironmentChange(ChangeFields& f) {
    EnvironmentChange c;
    c.value.radiance = f.colour("radiance");
    c.value.rotateDeg = f.finite("rotateDeg");
    return c;
}

}  // namespace

void writeSceneChange(ByteWriter& out, const SceneChange& change) {
    std::visit([&](const auto& c) { write(out, c); }, change);
}

SceneChange readSceneChange(ByteReader& in, std::uint32_t index) {
    const std::uint8_t tag = in.u8();
    switch (static_cast<ChangeTag>(tag)) {
        case ChangeTag::Camera: {
            ChangeFields f(in, index, "camera");
            return readCameraChange(f);
        }
        case ChangeTag::Transform: {
            ChangeFields f(in, index, "transform");
            return readTransformChange(f);
        }
        case ChangeTag::PunctualLight: {
            ChangeFields f(in, index, "punctual light");
            return readPunctualLightChange(f);
        }
        case ChangeTag::QuadLight: {
            ChangeFields f(in, index, "quad light");
            return readQuadLightChange(f);
        }
        case ChangeTag::Material: {
            ChangeFields f(in, index, "material");
            return readMaterialChange(f);
        }
        case ChangeTag::Environment: {
            ChangeFields f(in, index, "environment");
            return readEnvironmentChange(f);
        }
        case ChangeTag::Settings:
            return SettingsChange{readRenderSettings(in)};
    }
    in.fail("change " + std::to_string(index) + ": unknown tag " + std::to_string(tag) +
            ", expected 0 .. 6");
}

void writeSceneChanges(ByteWriter& out, const std::vector<SceneChange>& changes) {
    if (changes.size() > kMaxSceneChanges)
        throw ProtocolError(std::to_string(changes.size()) + " scene changes exceed the limit of " +
                            std::to_string(kMaxSceneChanges));
    out.u32(static_cast<std::uint32_t>(changes.size()));
    for (const SceneChange& c : changes) writeSceneChange(out, c);
}

std::vector<SceneChange> readSceneChanges(ByteReader& in) {
    const std::uint32_t count = in.u32();
    // Both checks come before the reserve: a few bytes claiming 2^31 changes allocate nothing.
    if (count > kMaxSceneChanges)
        in.fail(std::to_string(count) + " scene changes exceed the limit of " +
                std::to_string(kMaxSceneChanges));
    if (count > in.remaining() / kMinChangeBytes)
        in.fail(std::to_string(count) + " scene changes cannot fit in the " +
                std::to_string(in.remaining()) + " bytes left");
    std::vector<SceneChange> changes;
    changes.reserve(count);
    for (std::uint32_t i = 0; i < count; ++i) changes.push_back(readSceneChange(in, i));
    return changes;
}

}  // namespace igi::proto
