// setLobesAt writes every field of the Lobes it is given: eye paths build their lobes in place,
// in a ChainEnd that a delta chain reuses from vertex to vertex, so a field it skipped would
// keep the previous vertex's value. Here the storage starts full of another material's lobes
// (and of NaNs), and must end equal, field by field, to lobes built from scratch.

#include <cmath>
#include <cstring>
#include <limits>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "shading/Scattering.h"

namespace igi {
namespace {

// A field added to Lobes or SurfaceBrdf must be written by setLobesAt's paths and compared
// below; these sizes make that a compile error to forget.
static_assert(sizeof(SurfaceBrdf) == 64, "a new SurfaceBrdf field: compare it in expectSame");
static_assert(sizeof(Lobes) == 168, "a new Lobes field: write it in setLobesAt, compare it below");

void expectSame(glm::vec3 a, glm::vec3 b, const char* field) {
    for (int i = 0; i < 3; ++i)
        EXPECT_EQ(std::memcmp(&a[i], &b[i], sizeof(float)), 0)
            << field << "[" << i << "]: " << a[i] << " against " << b[i];
}

void expectSame(const Lobes& a, const Lobes& b) {
    expectSame(a.brdf.kd, b.brdf.kd, "brdf.kd");
    expectSame(a.brdf.ks, b.brdf.ks, "brdf.ks");
    EXPECT_EQ(a.brdf.exponent, b.brdf.exponent);
    expectSame(a.brdf.normal, b.brdf.normal, "brdf.normal");
    expectSame(a.brdf.mirror, b.brdf.mirror, "brdf.mirror");
    EXPECT_EQ(a.brdf.model, b.brdf.model);
    EXPECT_EQ(a.brdf.diffuseShare, b.brdf.diffuseShare);
    EXPECT_EQ(a.brdf.glossyShare, b.brdf.glossyShare);
    expectSame(a.reflection, b.reflection, "reflection");
    expectSame(a.transmission, b.transmission, "transmission");
    expectSame(a.normal, b.normal, "normal");
    expectSame(a.faceNormal, b.faceNormal, "faceNormal");
    expectSame(a.wo, b.wo, "wo");
    expectSame(a.mirrorDirection, b.mirrorDirection, "mirrorDirection");
    expectSame(a.refractDirection, b.refractDirection, "refractDirection");
    EXPECT_EQ(a.roughAlpha, b.roughAlpha);
    EXPECT_EQ(a.eta, b.eta);
    expectSame(a.tint, b.tint, "tint");
}

Material material(Reflection reflection, bool glass, float roughness) {
    Material m;
    m.diffuse = glm::vec3(0.6f, 0.5f, 0.4f);
    m.specular = glm::vec3(0.3f);
    m.phongExponent = 20.0f;
    m.reflection = reflection;
    m.glass = glass;
    m.roughness = roughness;
    m.transmittance = glm::vec3(0.9f, 0.8f, 0.7f);
    return m;
}

SurfacePoint hitOn(const Material& m) {
    SurfacePoint hit;
    hit.position = glm::vec3(0.1f, 0.2f, 0.3f);
    hit.geometricNormal = glm::vec3(0, 0, 1);
    hit.shadingNormal = glm::normalize(glm::vec3(0.1f, -0.05f, 1.0f));
    hit.albedo = m.diffuse;
    hit.roughness = m.roughness;
    hit.material = &m;
    return hit;
}

TEST(SetLobesAt, WritesEveryFieldWhateverTheStorageHeld) {
    const Material materials[] = {
        material(Reflection::None, false, 1.0f),   material(Reflection::Glossy, false, 1.0f),
        material(Reflection::Mirror, false, 1.0f), material(Reflection::Ggx, false, 0.5f),
        material(Reflection::Ggx, false, 0.0f),    material(Reflection::None, true, 1.0f),
        material(Reflection::Ggx, true, 0.6f),
    };
    const glm::vec3 views[] = {glm::normalize(glm::vec3(0.3f, 0.2f, 1.0f)),
                               glm::normalize(glm::vec3(-0.2f, 0.4f, -1.0f))};  // both sides
    for (const Material& m : materials) {
        const SurfacePoint hit = hitOn(m);
        for (glm::vec3 wo : views) {
            const Lobes fresh = lobesAt(hit, wo);
            // Storage that held every other material's lobes, and storage of NaNs.
            for (const Material& other : materials) {
                Lobes reused = lobesAt(hitOn(other), -wo);
                setLobesAt(hit, wo, reused);
                SCOPED_TRACE(::testing::Message()
                             << "reflection " << int(m.reflection) << " glass " << m.glass
                             << " after " << int(other.reflection) << " glass " << other.glass);
                expectSame(reused, fresh);
            }
            Lobes nans;
            const float nan = std::numeric_limits<float>::quiet_NaN();
            nans.reflection = nans.transmission = nans.refractDirection = nans.tint =
                glm::vec3(nan);
            nans.roughAlpha = nans.eta = nan;
            setLobesAt(hit, wo, nans);
            expectSame(nans, fresh);
        }
    }
}

}  // namespace
}  // namespace igi
