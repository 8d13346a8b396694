#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "Ggx.h"
#include "math/Color.h"
#include "math/Warp.h"

namespace igi {

/// Which glossy lobe a SurfaceBrdf has besides its Lambertian one.
enum class GlossyModel : std::uint8_t {
    /// A normalized Phong lobe of weight ks and exponent n (OBJ/MTL materials):
    ///   ks (n + 2) / (2 pi) cos^n(alpha),
    /// alpha the angle between wi and the mirror direction of wo (the same as between wo and the
    /// mirror direction of wi: f is reciprocal).
    Phong,
    /// glTF metallic-roughness's GGX lobe of Fresnel reflectance f0 and roughness alpha
    /// (client/Ggx.h).
    Ggx,
};

/// The non-delta part of a material at a surface point, on one side of it, seen from wo: a
/// Lambertian lobe of albedo kd and a glossy lobe (GlossyModel). Directions point away from
/// the surface.
struct SurfaceBrdf {
    glm::vec3 kd{0.0f};
    /// Phong: the lobe's weight. GGX: its Fresnel reflectance seen from wo, F(f0, n.wo), an
    /// estimate of its albedo for choosing lobes. Zero when the material has no glossy lobe.
    glm::vec3 ks{0.0f};
    float exponent = 0;      ///< Phong
    glm::vec3 normal{0.0f};  ///< shading normal on the side the directions leave to
    glm::vec3 wo{0.0f};      ///< toward the viewer
    glm::vec3 mirror{0.0f};  ///< wo mirrored about `normal`
    GlossyModel model = GlossyModel::Phong;
    float alpha = 0;     ///< GGX: roughness^2, at least ggx::kMinAlpha
    glm::vec3 f0{0.0f};  ///< GGX: Fresnel reflectance at normal incidence
    /// The lobes' shares of the albedo, mean(kd) : mean(ks) (GGX: mean(f0)), summing to one
    /// (or both zero). They weigh the lobes' sharpness, and must not depend on wo: both ends of
    /// a VPL connection evaluate it.
    float diffuseShare = 0;
    float glossyShare = 0;
    /// The probabilities with which sample() draws each lobe (the shares for Phong; for GGX
    /// mean(kd) : mean(ks), which follows the Fresnel reflectance toward grazing views).
    float sampleDiffuse = 0;
    float sampleGlossy = 0;

    /// A Lambertian lobe and a Phong lobe (ks zero: none).
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
        b.sampleDiffuse = b.diffuseShare;
        b.sampleGlossy = b.glossyShare;
        return b;
    }

    /// A Lambertian lobe and a GGX lobe (f0 zero: none), seen from wo.
    static SurfaceBrdf makeGgx(glm::vec3 kd, glm::vec3 f0, float alpha, glm::vec3 normal,
                               glm::vec3 wo, glm::vec3 mirror) {
        SurfaceBrdf b;
        b.model = GlossyModel::Ggx;
        b.kd = kd;
        b.f0 = f0;
        b.alpha = std::max(alpha, ggx::kMinAlpha);
        b.normal = normal;
        b.wo = wo;
        b.mirror = mirror;
        if (!isBlack(f0)) b.ks = ggx::schlick(f0, std::max(0.0f, glm::dot(normal, wo)));
        const float d = meanComponent(kd), g = meanComponent(f0), total = d + g;
        if (total > 0) {
            b.diffuseShare = d / total;
            b.glossyShare = g / total;
        }
        const float gs = meanComponent(b.ks), sampled = d + gs;
        if (sampled > 0) {
            b.sampleDiffuse = d / sampled;
            b.sampleGlossy = gs / sampled;
        }
        return b;
    }

    bool empty() const { return !(diffuseShare > 0) && !(glossyShare > 0); }
    bool hasGlossy() const { return glossyShare > 0; }

    /// Phong: cos^n(alpha), 0 behind the lobe.
    float lobe(float cosAlpha) const {
        return cosAlpha > 0 ? std::pow(std::min(cosAlpha, 1.0f), exponent) : 0.0f;
    }
    /// The glossy lobe's value toward w (no cosine of incidence).
    glm::vec3 glossy(glm::vec3 w) const {
        if (model == GlossyModel::Ggx) return ggx::evaluate(alpha, f0, normal, w, wo);
        return ks * ((exponent + 2.0f) * (0.5f * kInvPi) * lobe(glm::dot(w, mirror)));
    }
    glm::vec3 diffuse() const { return kd * kInvPi; }

    /// pi times f normalized to unit albedo, as one number: 1 on a Lambertian surface, up to
    /// (n + 2) / 2 in the peak of a pure Phong lobe (GGX: ggx::sharpness). The bound on VPL
    /// connections (ConnectionBound) is written in it, so that it does not depend on colours or
    /// textures.
    float sharpness(glm::vec3 w) const {
        if (model == GlossyModel::Ggx)
            return diffuseShare + glossyShare * ggx::sharpness(alpha, normal, w, wo);
        return diffuseShare + glossyShare * (0.5f * (exponent + 2.0f)) * lobe(glm::dot(w, mirror));
    }
    float maxSharpness() const {
        if (model == GlossyModel::Ggx) return diffuseShare + glossyShare * ggx::maxSharpness(alpha);
        return diffuseShare + glossyShare * 0.5f * (exponent + 2.0f);
    }

    /// Samples the mixture of the two lobes (cosine-weighted with probability sampleDiffuse,
    /// the glossy lobe otherwise: Phong about the mirror direction, GGX by visible normals).
    glm::vec3 sample(glm::vec2 u, float uLobe) const;
    /// The mixture's density (solid angle) of direction w.
    float pdf(glm::vec3 w) const {
        const float cosTheta = glm::dot(w, normal);
        float p = 0;
        if (sampleDiffuse > 0 && cosTheta > 0) p += sampleDiffuse * cosTheta * kInvPi;
        if (sampleGlossy > 0) {
            if (model == GlossyModel::Ggx)
                p += sampleGlossy * ggx::pdf(alpha, normal, w, wo);
            else
                p += sampleGlossy * (exponent + 1.0f) * (0.5f * kInvPi) * lobe(glm::dot(w, mirror));
        }
        return p;
    }
};

}  // namespace igi
