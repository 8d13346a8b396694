#pragma once

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace igi {

/// Mirror direction of `wi` (pointing away from the surface) about `n`.
inline glm::vec3 reflect(glm::vec3 wi, glm::vec3 n) {
    return 2.0f * glm::dot(wi, n) * n - wi;
}

/// Unpolarized Fresnel reflectance of a dielectric interface. cosI is the cosine of the incident
/// direction with the normal on the incident side (> 0); eta = n_transmitted / n_incident.
/// Returns 1 for total internal reflection and, through cosT, the transmitted cosine.
inline float fresnelDielectric(float cosI, float eta, float& cosT) {
    const float sin2T = (1.0f - cosI * cosI) / (eta * eta);
    if (sin2T >= 1.0f) {
        cosT = 0;
        return 1.0f;
    }
    cosT = std::sqrt(std::max(0.0f, 1.0f - sin2T));
    const float rs = (cosI - eta * cosT) / (cosI + eta * cosT);
    const float rp = (eta * cosI - cosT) / (eta * cosI + cosT);
    return 0.5f * (rs * rs + rp * rp);
}

/// Refracted direction of `wi` (pointing away, on the side of `n`), given eta and cosT from
/// fresnelDielectric.
inline glm::vec3 refract(glm::vec3 wi, glm::vec3 n, float eta, float cosT) {
    const float cosI = glm::dot(wi, n);
    return glm::normalize(-wi / eta + (cosI / eta - cosT) * n);
}

}  // namespace igi
