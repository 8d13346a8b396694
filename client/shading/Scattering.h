#pragma once

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "materials/SurfaceBrdf.h"
#include "tracing/SurfacePoint.h"

namespace igi {

/// The BSDF components of a material at a surface point, seen from direction wo (unit, pointing
/// away from the surface): two non-delta lobes that are evaluated for any pair of directions
/// (Lambertian and a normalized Phong lobe: together `brdf`) and two delta lobes that only
/// sampling can follow (a mirror, or the Fresnel reflection of glass; glass's refraction).
/// Eye paths evaluate the non-delta lobes at their end point and follow the delta ones; light
/// paths, photons and the path tracer choose one lobe at random.
///
/// Rough glass (glass whose alpha = roughness^2 is at least kMinGgxAlpha) is one lobe, the
/// GGX BSDF of its interface (client/materials/RoughDielectric.h: reflection and refraction
/// together), which `transmission` stands for: a lobe followed by sampling as glass is (its
/// weight the interface's albedo estimate F + (1 - F) tint at the macro normal), that only the
/// path tracer also evaluates (roughGlassValue, roughGlassPdf) for its light samples.
struct Lobes {
    SurfaceBrdf brdf;              ///< the non-delta part, oriented to wo's side
    glm::vec3 reflection{0.0f};    ///< delta: mirror Ks, or the Fresnel reflectance of glass
    glm::vec3 transmission{0.0f};  ///< delta: glass, (1 - F) times its transmittance
    glm::vec3 normal{0.0f};        ///< shading normal on wo's side
    glm::vec3 faceNormal{0.0f};    ///< geometric normal on wo's side, for ray offsets
    glm::vec3 wo{0.0f};
    glm::vec3 mirrorDirection{0.0f};  ///< wo reflected about the shading normal
    glm::vec3 refractDirection{0.0f};
    float roughAlpha = 0;  ///< rough glass: its alpha (>= kMinGgxAlpha); 0 otherwise
    float eta = 1;         ///< glass: the index below `normal` over the one above; 1 otherwise
    glm::vec3 tint{1.0f};  ///< rough glass: its transmittance (refraction only)

    bool hasNonDelta() const { return !brdf.empty(); }
    bool hasDelta() const;
    bool roughGlass() const { return roughAlpha > 0; }
};

/// The lobes at `hit` seen from wo, written into `l` (every field): where lobes are kept in a
/// larger struct (a ChainEnd), so that they are not built in a temporary and copied there (a
/// copy that reads with 16-byte loads what was just written 4 and 8 bytes at a time waits for
/// the stores to drain, on every eye path).
void setLobesAt(const SurfacePoint& hit, glm::vec3 wo, Lobes& l);
inline Lobes lobesAt(const SurfacePoint& hit, glm::vec3 wo) {
    Lobes l;
    setLobesAt(hit, wo, l);
    return l;
}

enum class Lobe { Diffuse, Glossy, Reflection, Transmission };

/// The lobe's share of the light: its mean albedo (for glossy, Ks).
float lobeWeight(const Lobes& lobes, Lobe lobe);

/// Picks one lobe with probability proportional to its weight; false if all are zero. With
/// `roulette`, the probabilities are the lobes' largest channels when they sum to less than
/// one, and the rest is absorption (false): Russian roulette by albedo, under which no
/// channel of a surviving path's throughput grows.
bool chooseLobe(const Lobes& lobes, float u, Lobe& lobe, float& probability, bool roulette = false);

/// Picks one of the delta lobes only (mirror or glass), as chooseLobe; false if there is none.
bool chooseDeltaLobe(const Lobes& lobes, float u, Lobe& lobe, float& probability,
                     bool roulette = false);

/// Samples a continuation in one lobe: the direction and its weight (the lobe's BSDF times
/// cosine over the lobe's own pdf; the lobe's choice is the caller's). Diffuse, glossy and
/// rough glass use u, rough glass uChoice too (reflection or refraction); mirrors and smooth
/// glass ignore both. False when the direction goes through the surface (a shading-normal
/// artefact, a Phong direction below the horizon, a rough glass direction on the wrong side).
bool sampleLobe(const Lobes& lobes, Lobe lobe, glm::vec2 u, float uChoice, glm::vec3& direction,
                glm::vec3& weight);

/// A fresh uniform number from the one that chose a lobe of probability `probability` that is
/// the first lobe with weight (as rough glass's only lobe is): u / probability, below one.
float remapChoice(float u, float probability);

/// Rough glass: its BSDF toward wi (the tint on refraction), and the density with which
/// sampleLobe draws wi; zero where wi is on the wrong side of the geometric surface.
glm::vec3 roughGlassValue(const Lobes& lobes, glm::vec3 wi);
float roughGlassPdf(const Lobes& lobes, glm::vec3 wi);

/// What an eye path multiplies a weight of sampleLobe or a value of roughGlassValue toward wi
/// by. Those are importance's (what light paths carry: power, which refraction does not
/// scale); radiance is compressed into the denser side's smaller solid angles, so refraction
/// scales it by (eta_wo / eta_wi)^2: 1 / eta^2 into the glass, eta^2 out of it, 1 for
/// reflection and for every other material. For a closed object with the camera and the
/// lights outside it the two cancel; a light inside glass (or a camera) needs it, or eye paths
/// and light paths disagree by eta^2 on the light it sends out.
inline float radianceScale(const Lobes& lobes, glm::vec3 wi) {
    if (lobes.eta == 1.0f || glm::dot(wi, lobes.faceNormal) >= 0.0f) return 1.0f;
    return 1.0f / (lobes.eta * lobes.eta);
}

/// Whether a lobe is a delta lobe (mirror or glass).
inline bool isDelta(Lobe lobe) {
    return lobe == Lobe::Reflection || lobe == Lobe::Transmission;
}

}  // namespace igi
