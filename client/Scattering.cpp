#include "Scattering.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "math/Color.h"
#include "math/Frame.h"
#include "math/Optics.h"
#include "math/Warp.h"

namespace igi {

Lobes lobesAt(const SurfacePoint& hit, glm::vec3 wo) {
    Lobes l;
    const Material& m = *hit.material;
    const bool front = glm::dot(wo, hit.geometricNormal) >= 0;
    l.faceNormal = front ? hit.geometricNormal : -hit.geometricNormal;
    l.normal = front ? hit.shadingNormal : -hit.shadingNormal;
    l.wo = wo;
    l.mirrorDirection = reflect(wo, l.normal);
    if (m.glass) {
        // Front (counter-clockwise) side is outside: entering the glass from the front.
        const float eta = front ? m.ior : 1.0f / m.ior;
        float cosT = 0;
        const float cosI = std::max(1e-6f, glm::dot(wo, l.normal));
        const float f = fresnelDielectric(cosI, eta, cosT);
        l.reflection = glm::vec3(f);
        if (f < 1.0f) {
            l.transmission = (1.0f - f) * m.transmittance;
            l.refractDirection = refract(wo, l.normal, eta, cosT);
        }
        return l;
    }
    l.diffuse = hit.albedo;
    if (m.reflection != Reflection::None) {
        l.reflection = m.specular;
        l.glossy = m.reflection == Reflection::Glossy;
        l.exponent = m.phongExponent;
    }
    return l;
}

bool chooseLobe(const Lobes& l, float u, Lobe& lobe, float& probability) {
    const float wd = meanComponent(l.diffuse), wr = meanComponent(l.reflection),
                wt = meanComponent(l.transmission);
    const float total = wd + wr + wt;
    if (!(total > 0)) return false;
    u *= total;
    if (u < wd) {
        lobe = Lobe::Diffuse;
        probability = wd / total;
    } else if (u < wd + wr || wt <= 0) {
        lobe = Lobe::Reflection;
        probability = wr / total;
    } else {
        lobe = Lobe::Transmission;
        probability = wt / total;
    }
    return probability > 0;
}

bool sampleSpecular(const Lobes& l, Lobe lobe, glm::vec2 u, glm::vec3& direction,
                    glm::vec3& weight) {
    if (lobe == Lobe::Transmission) {
        direction = l.refractDirection;
        weight = l.transmission;
        return glm::dot(direction, l.faceNormal) < 0;
    }
    if (!l.glossy) {
        direction = l.mirrorDirection;
        weight = l.reflection;
        return glm::dot(direction, l.faceNormal) > 0;
    }
    // Normalized Phong: f = Ks (n + 2) / (2 pi) cos^n(alpha), sampled with pdf
    // (n + 1) / (2 pi) cos^n(alpha) about the mirror direction, so f cos / pdf is below.
    direction = Frame(l.mirrorDirection).toWorld(squareToPhongLobe(u, l.exponent));
    const float cosTheta = glm::dot(direction, l.normal);
    if (cosTheta <= 0 || glm::dot(direction, l.faceNormal) <= 0) return false;
    weight = l.reflection * ((l.exponent + 2.0f) / (l.exponent + 1.0f) * cosTheta);
    return true;
}

glm::vec3 glossyBrdf(const Lobes& l, glm::vec3 wi) {
    const float cosAlpha = std::max(0.0f, glm::dot(wi, l.mirrorDirection));
    return l.reflection * ((l.exponent + 2.0f) / (2.0f * kPi) * std::pow(cosAlpha, l.exponent));
}

}  // namespace igi
