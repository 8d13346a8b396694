// A VPL on a normal-mapped surface bends the map's normal for the direction toward each
// receiver (Vpl::bends), as the eye path and the path tracer bend a surface's normal for the
// direction toward the camera: what it sends a receiver is what the path tracer's light sample
// at that vertex evaluates, f(light's direction, toward the receiver) about the normal bent
// for the receiver. Before, the VPL kept the normal bent for the light's direction, and at
// grazing light on a strongly tilted map the two differed (the test counts where).

#include "lights/VplOnSurface.h"

#include <cmath>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "math/Color.h"
#include "shading/Scattering.h"

namespace igi {
namespace {

TEST(VplOnSurface, AMappedVplSendsWhatThePathTracerEvaluatesTowardEachReceiver) {
    Material m;
    m.reflection = Reflection::Ggx;
    m.normalTexture = 0;  // normal-mapped: the shading normal below is the map's
    m.ior = 1.5f;
    SurfacePoint hit;
    hit.material = &m;
    hit.geometricNormal = glm::vec3(0, 0, 1);
    hit.shadingNormal = glm::normalize(glm::vec3(0.6f, 0.0f, 0.8f));  // tilted 37 degrees
    hit.albedo = glm::vec3(0.8f, 0.6f, 0.4f);
    hit.metallic = 0.5f;
    hit.roughness = 0.4f;
    // Light from a grazing direction on the side the map tilts away from: below the mapped
    // normal, so the light's lobes bend it.
    const glm::vec3 in = glm::normalize(glm::vec3(-0.95f, 0.1f, 0.3f));
    const Lobes lit = lobesAt(hit, in);
    ASSERT_GT(glm::length(lit.normal - hit.shadingNormal), 0.05f) << "the light's bend";
    const glm::vec3 flux(1.0f);
    const Vpl v = vplOnSurface(hit, lit, flux);
    ASSERT_TRUE(v.bends);
    int checked = 0, bentOtherwise = 0;
    for (int i = 0; i < 24; ++i) {
        for (int j = 1; j < 12; ++j) {
            const float phi = 2.0f * kPi * float(i) / 24.0f, cosTheta = float(j) / 12.0f;
            const float s = std::sqrt(1.0f - cosTheta * cosTheta);
            const glm::vec3 out(s * std::cos(phi), s * std::sin(phi), cosTheta);  // to receiver
            const Lobes eye = lobesAt(hit, out);  // the path tracer at this vertex
            const glm::vec3 f = eye.brdf.diffuse() + eye.brdf.glossy(in);
            const glm::vec3 sent = v.towards(-out).intensity;
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(sent[c], flux[c] * f[c], 1e-4f * (1.0f + f[c])) << i << " " << j;
            EXPECT_NEAR(v.emittingCosine(-out), glm::dot(eye.normal, out), 1e-5f);
            ++checked;
            // Where the receiver's bend differs from the light's, the light's normal (what the
            // VPL used before) evaluates another BRDF.
            if (glm::length(eye.normal - v.normal) > 0.01f) {
                const glm::vec3 old =
                    v.power + v.glossyPower * ggx::evaluate(v.exponent, v.f0, v.normal, in, out);
                if (std::abs(luminance(old) - luminance(f)) > 0.05f * luminance(f)) ++bentOtherwise;
            }
        }
    }
    EXPECT_EQ(checked, 24 * 11);
    std::printf("%d of %d receivers see another BRDF through the light's bend\n", bentOtherwise,
                checked);
    EXPECT_GT(bentOtherwise, 10);
    // Below the geometric surface the VPL lights nothing.
    EXPECT_LE(v.emittingCosine(glm::normalize(glm::vec3(0.3f, 0.0f, 0.5f))), 0.0f);
}

}  // namespace
}  // namespace igi
