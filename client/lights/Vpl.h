#pragma once

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "materials/Ggx.h"
#include "materials/NormalMap.h"
#include "scene/Light.h"

namespace igi {

/// A virtual point light: a point on a light source (a light sample) or a non-delta vertex of a
/// light path (an indirect VPL).
///
/// Toward a unit direction w it sends the radiant intensity
///   (power + glossyPower * cos^exponent(w, mirror)) * cos(theta),
/// theta measured from `normal` (for an omni light sample, a point light: `power` alone), so a
/// point at distance d whose normal makes the angle theta_x with -w receives that times
/// cos(theta_x) / d^2. For an indirect VPL `power` is the flux that arrived times kd / pi and
/// glossyPower that flux times the Phong lobe's ks (n + 2) / (2 pi): the VPL carries its
/// surface's BRDF, evaluated toward whatever it lights. On a GGX surface (`ggx`) glossyPower is
/// the flux that arrived from the mirror image of `mirror`, and the lobe's factor is the GGX
/// BRDF f(that direction, -w) (client/materials/Ggx.h) instead of the Phong lobe.
struct Vpl {
    glm::vec3 position{0.0f};  ///< already moved off its surface: shadow rays end here
    glm::vec3 normal{0.0f};
    glm::vec3 power{0.0f};
    bool omni = false;
    /// An omni light sample of a spot light: `normal` is its axis, and toward -w it sends
    /// power times spotRamp(spotCosOuter, spotScale, cos to the axis).
    bool spot = false;
    float spotCosOuter = -1.0f, spotScale = 0.0f;
    bool ggx = false;  ///< a GGX lobe: `exponent` is its alpha (client/materials/Ggx.h)

    // Indirect VPLs on glossy surfaces.
    glm::vec3 glossyPower{0.0f};
    float exponent = 0;
    glm::vec3 mirror{0.0f};  ///< the direction the light came from, mirrored about `normal`
    glm::vec3 f0{0.0f};      ///< GGX: the lobe's Fresnel reflectance at normal incidence
    /// Its surface's SurfaceBrdf::diffuseShare and glossyShare, for the connection bound.
    float diffuseShare = 1;
    float glossyShare = 0;

    /// On a normal- or bump-mapped surface: the shading normal as the map gives it (before the
    /// bend of NormalMap.h's ensureValidReflection) and the geometric normal, both on the lit
    /// side. `normal` is then the map's normal bent for the direction the light came from,
    /// which only the light path's next bounce uses: toward a receiver the VPL bends `mapped`
    /// for the direction toward that receiver (normalToward), as the eye path and the path
    /// tracer bend a surface's normal for the direction toward the camera. So the bend depends
    /// on the same direction at both ends of a connection, and a VPL sends what the path
    /// tracer's light sample at that vertex evaluates (docs/MATERIALS.md).
    bool bends = false;
    glm::vec3 mapped{0.0f};
    glm::vec3 face{0.0f};

    /// Light samples on area lights: the area density with which the point was chosen, for
    /// multiple importance sampling against BRDF sampling (0 for point lights).
    float areaPdf = 0;

    bool glossy() const { return glossyShare > 0; }
    /// The shading normal toward a receiver in the unit direction -w (w: from the receiver to
    /// the VPL): `normal`, or on a mapped surface `mapped` bent for -w; zero where -w is below
    /// the geometric surface (no connection leaves a surface below it).
    glm::vec3 normalToward(glm::vec3 w) const {
        if (!bends) return normal;
        if (!(-glm::dot(face, w) > 0)) return glm::vec3(0.0f);
        return normalmap::ensureValidReflection(face, -w, mapped);
    }
    /// The cosine factor at the VPL toward a receiver in the unit direction -w: cos(theta) from
    /// its normal, 1 for a point light, the ramp for a spot.
    float emittingCosine(glm::vec3 w) const {
        if (!omni) return -glm::dot(normalToward(w), w);
        return spot ? spotRamp(spotCosOuter, spotScale, -glm::dot(normal, w)) : 1.0f;
    }
    /// The direction the light came from (mirror's image about the normal).
    glm::vec3 incoming() const { return 2.0f * glm::dot(normal, mirror) * normal - mirror; }
    bool operator==(const Vpl&) const = default;

    /// What the VPL sends towards a receiver in the unit direction -w (w: from the receiver to
    /// the VPL), its cosine left out: the intensity, and its BRDF's sharpness that way for the
    /// connection bound (client/shading/ConnectionBound.h).
    struct Emission {
        glm::vec3 intensity;
        float sharpness;
    };
    Emission towards(glm::vec3 w) const {
        Emission e{power, diffuseShare};
        if (!glossy()) return e;
        const glm::vec3 n = normalToward(w);
        if (ggx) {
            const glm::vec3 in = incoming();
            e.intensity += glossyPower * ggx::evaluate(exponent, f0, n, in, -w);
            e.sharpness += glossyShare * ggx::sharpness(exponent, n, in, -w);
        } else {
            // Phong about the mirror direction of where the light came from (on a mapped
            // surface, mirrored about the normal bent toward the receiver).
            const glm::vec3 m = bends ? 2.0f * glm::dot(n, incoming()) * n - incoming() : mirror;
            const float c = -glm::dot(w, m);
            const float lobe = c > 0 ? std::pow(std::min(c, 1.0f), exponent) : 0.0f;
            e.intensity += glossyPower * lobe;
            e.sharpness += glossyShare * 0.5f * (exponent + 2.0f) * lobe;
        }
        return e;
    }
};

/// The glossy lobe's intensity (its cosine left out) in the unit direction `out` leaving v.
inline glm::vec3 glossyIntensity(const Vpl& v, glm::vec3 out) {
    if (!v.glossy()) return glm::vec3(0.0f);
    const glm::vec3 n = v.normalToward(-out);
    if (v.ggx) return v.glossyPower * ggx::evaluate(v.exponent, v.f0, n, v.incoming(), out);
    const glm::vec3 m = v.bends ? 2.0f * glm::dot(n, v.incoming()) * n - v.incoming() : v.mirror;
    const float c = glm::dot(out, m);
    return c > 0 ? v.glossyPower * std::pow(std::min(c, 1.0f), v.exponent) : glm::vec3(0.0f);
}

/// Shadow rays toward a VPL stop this fraction of the distance short of it: it sits on a
/// surface of its own.
constexpr float kVplShadowShrink = 1e-4f;

}  // namespace igi
