#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "SurfacePoint.h"

namespace igi {

/// The BSDF components of a material at a surface point, seen from direction wo (unit, pointing
/// away from the surface): a Lambertian part, a specular or glossy reflection, and for glass a
/// refraction. Eye paths split into these at their first hit; light paths, photons and later
/// eye bounces choose one of them at random.
struct Lobes {
    glm::vec3 diffuse{0.0f};       ///< Lambertian albedo
    glm::vec3 reflection{0.0f};    ///< mirror or glossy Ks, or the Fresnel reflectance of glass
    glm::vec3 transmission{0.0f};  ///< glass: (1 - F) times its transmittance
    glm::vec3 normal{0.0f};        ///< shading normal on wo's side
    glm::vec3 faceNormal{0.0f};    ///< geometric normal on wo's side, for ray offsets
    glm::vec3 wo{0.0f};
    glm::vec3 mirrorDirection{0.0f};
    glm::vec3 refractDirection{0.0f};
    bool glossy = false;
    float exponent = 0;

    bool hasDiffuse() const { return diffuse.x > 0 || diffuse.y > 0 || diffuse.z > 0; }
};

Lobes lobesAt(const SurfacePoint& hit, glm::vec3 wo);

enum class Lobe { Diffuse, Reflection, Transmission };

/// Picks one lobe with probability proportional to its mean weight; false if all are zero.
bool chooseLobe(const Lobes& lobes, float u, Lobe& lobe, float& probability);

/// Samples the continuation of a specular lobe: the direction and its weight (BSDF times cosine
/// over pdf). For a glossy lobe u picks a direction in the Phong lobe; mirrors and glass ignore
/// u. False when the direction would go through the surface (shading-normal artefacts).
bool sampleSpecular(const Lobes& lobes, Lobe lobe, glm::vec2 u, glm::vec3& direction,
                    glm::vec3& weight);

/// The normalized Phong BRDF of a glossy lobe toward wi (no cosine).
glm::vec3 glossyBrdf(const Lobes& lobes, glm::vec3 wi);

}  // namespace igi
