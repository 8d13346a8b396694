#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "materials/Ggx.h"
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
    /// glTF metallic-roughness's GGX lobe (client/materials/Ggx.h): ks is its Fresnel reflectance
    /// at
    /// normal incidence f0, `exponent` its alpha.
    Ggx,
};

/// The non-delta part of a material at a surface point, on one side of it, seen from the
/// direction whose mirror image about `normal` is `mirror`: a Lambertian lobe of albedo kd and
/// a glossy lobe (GlossyModel). Directions point away from the surface.
///
/// Kept small: eye paths make and copy one per pixel. The Phong fields carry GGX's parameters
/// (ks its f0, exponent its alpha), and the view direction is mirror's image.
struct SurfaceBrdf {
    glm::vec3 kd{0.0f};
    glm::vec3 ks{0.0f};      ///< Phong: the lobe's weight; GGX: f0. Zero: no glossy lobe
    float exponent = 0;      ///< Phong: the exponent; GGX: alpha = roughness^2 (>= ggx::kMinAlpha)
    glm::vec3 normal{0.0f};  ///< shading normal on the side the directions leave to
    glm::vec3 mirror{0.0f};  ///< the direction of view mirrored about `normal`
    GlossyModel model = GlossyModel::Phong;
    /// The lobes' shares of the albedo, mean(kd) : mean(ks), summing to one (or both zero).
    /// They weigh the lobes' sharpness and, for Phong, choose the lobe to sample. They must
    /// not depend on the direction of view: both ends of a VPL connection evaluate them.
    float diffuseShare = 0;
    float glossyShare = 0;

    /// A Lambertian lobe and a Phong lobe (ks zero: none). Set `mirror` before evaluating it.
    static SurfaceBrdf make(glm::vec3 kd, glm::vec3 ks, float exponent, glm::vec3 normal) {
        SurfaceBrdf b;
        b.setPhong(kd, ks, exponent, normal, glm::vec3(0.0f));
        return b;
    }
    /// make()'s lobes with `mirror`, every field written in place (lobesAt builds them inside
    /// a larger struct: made on the stack and copied there, the copy's 16-byte loads would wait
    /// for the narrower stores that made them).
    void setPhong(glm::vec3 kd_, glm::vec3 ks_, float exponent_, glm::vec3 normal_,
                  glm::vec3 mirror_) {
        kd = kd_;
        ks = ks_;
        exponent = exponent_;
        normal = normal_;
        mirror = mirror_;
        model = GlossyModel::Phong;
        const float d = meanComponent(kd_), g = meanComponent(ks_), total = d + g;
        diffuseShare = total > 0 ? d / total : 0.0f;
        glossyShare = total > 0 ? g / total : 0.0f;
    }

    /// A Lambertian lobe and a GGX lobe (f0 zero: none), seen from the mirror image of `mirror`.
    static SurfaceBrdf makeGgx(glm::vec3 kd, glm::vec3 f0, float alpha, glm::vec3 normal,
                               glm::vec3 mirror) {
        SurfaceBrdf b = make(kd, f0, std::max(alpha, ggx::kMinAlpha), normal);
        b.model = GlossyModel::Ggx;
        b.mirror = mirror;
        return b;
    }

    bool empty() const { return !(diffuseShare > 0) && !(glossyShare > 0); }
    bool hasGlossy() const { return glossyShare > 0; }

    /// The direction of view (GGX needs it; Phong only its mirror image).
    glm::vec3 view() const { return 2.0f * glm::dot(normal, mirror) * normal - mirror; }
    /// An estimate of the glossy lobe's albedo seen from the view, for choosing lobes: Phong's
    /// ks; GGX's Fresnel reflectance F(f0, n.wo), which grows toward grazing views.
    glm::vec3 glossyAlbedo() const {
        if (model == GlossyModel::Ggx && hasGlossy())
            return ggx::schlick(ks, std::max(0.0f, glm::dot(normal, mirror)));
        return ks;
    }

    /// Phong: cos^n(alpha), 0 behind the lobe.
    float lobe(float cosAlpha) const {
        return cosAlpha > 0 ? std::pow(std::min(cosAlpha, 1.0f), exponent) : 0.0f;
    }
    /// Phong: lobe() toward w, for the overloads below that take it: a connection that needs
    /// the lobe's value, sharpness and density toward one direction pays for one pow, not three.
    /// GGX: 0 (its overloads ignore it).
    float lobeToward(glm::vec3 w) const {
        return model == GlossyModel::Ggx ? 0.0f : lobe(glm::dot(w, mirror));
    }
    /// The glossy lobe's value toward w (no cosine of incidence).
    glm::vec3 glossy(glm::vec3 w) const { return glossy(w, lobeToward(w)); }
    /// The same, with lobeToward(w) given.
    glm::vec3 glossy(glm::vec3 w, float lobeW) const {
        if (model == GlossyModel::Ggx) return ggx::evaluate(exponent, ks, normal, w, view());
        return ks * ((exponent + 2.0f) * (0.5f * kInvPi) * lobeW);
    }
    glm::vec3 diffuse() const { return kd * kInvPi; }

    /// pi times f normalized to unit albedo, as one number: 1 on a Lambertian surface, up to
    /// (n + 2) / 2 in the peak of a pure Phong lobe (GGX: ggx::sharpness). The bound on VPL
    /// connections (ConnectionBound) is written in it, so that it does not depend on colours or
    /// textures.
    float sharpness(glm::vec3 w) const { return sharpness(w, lobeToward(w)); }
    /// The same, with lobeToward(w) given.
    float sharpness(glm::vec3 w, float lobeW) const {
        if (model == GlossyModel::Ggx)
            return diffuseShare + glossyShare * ggx::sharpness(exponent, normal, w, view());
        return diffuseShare + glossyShare * (0.5f * (exponent + 2.0f)) * lobeW;
    }
    float maxSharpness() const {
        if (model == GlossyModel::Ggx)
            return diffuseShare + glossyShare * ggx::maxSharpness(exponent);
        return diffuseShare + glossyShare * 0.5f * (exponent + 2.0f);
    }

    /// The probability with which sample() draws the glossy lobe: its share for Phong; for
    /// GGX mean(glossyAlbedo()) : mean(kd), which follows the Fresnel reflectance.
    float glossySampling() const {
        if (model != GlossyModel::Ggx || !hasGlossy()) return glossyShare;
        const float g = meanComponent(glossyAlbedo()), d = meanComponent(kd);
        return g / (g + d);
    }

    /// Samples the mixture of the two lobes (cosine-weighted, or the glossy lobe with
    /// probability glossySampling(): Phong about the mirror direction, GGX by visible normals).
    glm::vec3 sample(glm::vec2 u, float uLobe) const;
    /// The mixture's density (solid angle) of direction w.
    float pdf(glm::vec3 w) const { return pdf(w, glossyShare > 0 ? lobeToward(w) : 0.0f); }
    /// The same, with lobeToward(w) given.
    float pdf(glm::vec3 w, float lobeW) const {
        const float cosTheta = glm::dot(w, normal);
        if (model == GlossyModel::Ggx) {
            const float pGlossy = glossySampling();
            float p = cosTheta > 0 ? (1.0f - pGlossy) * cosTheta * kInvPi : 0.0f;
            if (pGlossy > 0) p += pGlossy * ggx::pdf(exponent, normal, w, view());
            return p;
        }
        float p = 0;
        if (diffuseShare > 0 && cosTheta > 0) p += diffuseShare * cosTheta * kInvPi;
        if (glossyShare > 0) p += glossyShare * (exponent + 1.0f) * (0.5f * kInvPi) * lobeW;
        return p;
    }
};

}  // namespace igi
