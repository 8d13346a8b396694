#pragma once

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "math/Color.h"
#include "math/Warp.h"

namespace igi {

/// The non-delta part of a material at a surface point, on one side of it: a Lambertian lobe
/// of albedo kd and a normalized Phong lobe of weight ks and exponent n,
///   f(wi, wo) = kd / pi + ks (n + 2) / (2 pi) cos^n(alpha),
/// alpha the angle between wi and the mirror direction of wo (the same as between wo and the
/// mirror direction of wi: f is reciprocal). Directions point away from the surface.
struct SurfaceBrdf {
    glm::vec3 kd{0.0f};
    glm::vec3 ks{0.0f};  ///< zero when the material has no glossy lobe
    float exponent = 0;
    glm::vec3 normal{0.0f};  ///< shading normal on the side the directions leave to
    /// The lobes' shares of the albedo, mean(kd) : mean(ks), summing to one (or both zero).
    float diffuseShare = 0;
    float glossyShare = 0;

    static SurfaceBrdf make(glm::vec3 kd, glm::vec3 ks, float exponent, glm::vec3 normal) {
        SurfaceBrdf b;
        b.kd = kd;
        b.ks = ks;
        b.exponent = exponent;
        b.normal = normal;
        const float d = meanComponent(kd), g = meanComponent(ks), total = d + g;
        if (total > 0) {
            b.diffuseShare = d / total;
            b.glossyShare = g / total;
        }
        return b;
    }

    bool empty() const { return !(diffuseShare > 0) && !(glossyShare > 0); }
    bool hasGlossy() const { return glossyShare > 0; }

    /// cos^n(alpha), 0 behind the lobe.
    float lobe(float cosAlpha) const {
        return cosAlpha > 0 ? std::pow(std::min(cosAlpha, 1.0f), exponent) : 0.0f;
    }
    /// The Phong lobe's value for cos(alpha) (no cosine of incidence).
    glm::vec3 glossy(float cosAlpha) const {
        return ks * ((exponent + 2.0f) * (0.5f * kInvPi) * lobe(cosAlpha));
    }
    glm::vec3 diffuse() const { return kd * kInvPi; }

    /// pi times f normalized to unit albedo, as one number: 1 on a Lambertian surface, up to
    /// (n + 2) / 2 in the peak of a pure Phong lobe. The bound on VPL connections
    /// (ConnectionBound) is written in it, so that it does not depend on colours or textures.
    float sharpness(float cosAlpha) const {
        return diffuseShare + glossyShare * (0.5f * (exponent + 2.0f)) * lobe(cosAlpha);
    }
    float maxSharpness() const { return diffuseShare + glossyShare * 0.5f * (exponent + 2.0f); }

    /// Samples the mixture of the two lobes (cosine-weighted with probability diffuseShare,
    /// the Phong lobe about `mirror` otherwise).
    glm::vec3 sample(glm::vec2 u, float uLobe, glm::vec3 mirror) const;
    /// The mixture's density (solid angle) of direction w; `mirror` as for sample().
    float pdf(glm::vec3 w, glm::vec3 mirror) const {
        const float cosTheta = glm::dot(w, normal);
        float p = 0;
        if (diffuseShare > 0 && cosTheta > 0) p += diffuseShare * cosTheta * kInvPi;
        if (glossyShare > 0)
            p += glossyShare * (exponent + 1.0f) * (0.5f * kInvPi) * lobe(glm::dot(w, mirror));
        return p;
    }
};

}  // namespace igi
