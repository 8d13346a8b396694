#include "shading/Scattering.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "materials/NormalMap.h"
#include "materials/RoughDielectric.h"
#include "math/Color.h"
#include "math/Frame.h"
#include "math/Optics.h"
#include "math/Warp.h"

namespace igi {

bool Lobes::hasDelta() const {
    return !isBlack(reflection) || !isBlack(transmission);
}

namespace {

// glTF metallic-roughness (Material.h, Reflection::Ggx). The diffuse lobe is weighed by
// 1 - f0 of the dielectric rather than the specification's 1 - F(v.h): a constant keeps it
// Lambertian, so that its light is irradiance times kd as the master filters it, and the BRDF
// reciprocal, as VPLs need (docs/MATERIALS.md).
void setGgx(const SurfacePoint& hit, Lobes& l) {
    const Material& m = *hit.material;
    const float metallic = std::clamp(hit.metallic, 0.0f, 1.0f);
    const float roughness = std::clamp(hit.roughness, 0.0f, 1.0f);
    const float r = (m.ior - 1.0f) / (m.ior + 1.0f);
    const float dielectricF0 = std::isfinite(r) ? std::min(r * r, 1.0f) : 0.04f;
    const glm::vec3 base = hit.albedo;
    const glm::vec3 f0 = glm::mix(glm::vec3(dielectricF0), base, metallic);
    const glm::vec3 kd = base * ((1.0f - metallic) * (1.0f - dielectricF0));
    const float alpha = roughness * roughness;
    if (alpha < kMinGgxAlpha) {  // a mirror of Fresnel reflectance over the diffuse lobe
        l.brdf = SurfaceBrdf::make(kd, glm::vec3(0.0f), 0.0f, l.normal);
        l.brdf.mirror = l.mirrorDirection;
        l.reflection = ggx::schlick(f0, std::max(0.0f, glm::dot(l.wo, l.normal)));
        return;
    }
    l.brdf = SurfaceBrdf::makeGgx(kd, f0, alpha, l.normal, l.mirrorDirection);
}

// OBJ's materials: a Lambertian and a Phong lobe, or a mirror over a Lambertian one, about the
// normal and mirror direction already in `l`.
inline void setPhong(const SurfacePoint& hit, Lobes& l) {
    const Material& m = *hit.material;
    const bool glossy = m.reflection == Reflection::Glossy && m.phongExponent >= 0;
    l.brdf.setPhong(hit.albedo, glossy ? m.specular : glm::vec3(0.0f), m.phongExponent, l.normal,
                    l.mirrorDirection);
    if (m.reflection == Reflection::Mirror) l.reflection = m.specular;
}

// Glass, GGX and normal- or bump-mapped materials: what the OBJ materials' path below leaves.
[[gnu::noinline]] void setOtherLobes(const SurfacePoint& hit, glm::vec3 wo, Lobes& l) {
    l = Lobes{};
    const Material& m = *hit.material;
    const bool front = glm::dot(wo, hit.geometricNormal) >= 0;
    l.faceNormal = front ? hit.geometricNormal : -hit.geometricNormal;
    l.normal = front ? hit.shadingNormal : -hit.shadingNormal;
    // A normal map can turn the shading normal away from wo while wo is above the geometric
    // surface: every GGX value and sample about it would be zero (black facets), the mirror
    // direction below the surface. The fix is Cycles' ensure_valid_reflection: the normal bent
    // toward the geometric one just enough that wo's mirror direction is above the surface
    // (NormalMap.h). Only for normal- and bump-mapped materials, so that scenes without them
    // (whose interpolated normals may do the same) render exactly as before.
    if (m.perturbsNormal()) l.normal = normalmap::ensureValidReflection(l.faceNormal, wo, l.normal);
    l.wo = wo;
    l.mirrorDirection = reflect(wo, l.normal);
    if (m.glass) {
        // Front (counter-clockwise) side is outside: entering the glass from the front.
        const float eta = front ? m.ior : 1.0f / m.ior;
        float cosT = 0;
        const float cosI = std::max(1e-6f, glm::dot(wo, l.normal));
        const float f = fresnelDielectric(cosI, eta, cosT);
        l.eta = eta;
        // Rough glass (glTF transmission with roughness): one lobe, the GGX BSDF of the
        // interface, weighed by its albedo estimate at the macro normal.
        if (m.reflection == Reflection::Ggx) {
            const float roughness = std::clamp(hit.roughness, 0.0f, 1.0f);
            const float alpha = roughness * roughness;
            if (alpha >= kMinGgxAlpha) {
                // An interpolated normal that turns away from wo (a silhouette of a smooth
                // mesh) leaves the BSDF without a side: the geometric normal stands in.
                if (!(glm::dot(wo, l.normal) > 1e-4f)) l.normal = l.faceNormal;
                l.roughAlpha = alpha;
                l.tint = m.transmittance;
                l.transmission = f + (1.0f - f) * m.transmittance;
                return;
            }
        }
        l.reflection = glm::vec3(f);
        if (f < 1.0f) {
            l.transmission = (1.0f - f) * m.transmittance;
            l.refractDirection = refract(wo, l.normal, eta, cosT);
        }
        return;
    }
    if (m.reflection == Reflection::Ggx) {
        setGgx(hit, l);
        return;
    }
    setPhong(hit, l);
}

}  // namespace

void setLobesAt(const SurfacePoint& hit, glm::vec3 wo, Lobes& l) {
    const Material& m = *hit.material;
    if (m.glass || m.reflection == Reflection::Ggx || m.perturbsNormal())
        return setOtherLobes(hit, wo, l);
    // OBJ's materials (Lambertian, Phong, mirror) on interpolated normals: what every eye path
    // of the Cornell scenes meets, kept free of calls (around a call GCC keeps wo and the
    // normals on the stack, and reloads them with loads that straddle its stores, a stall each).
    const bool front = glm::dot(wo, hit.geometricNormal) >= 0;
    const glm::vec3 normal = front ? hit.shadingNormal : -hit.shadingNormal;
    const glm::vec3 mirror = reflect(wo, normal);
    // Every field once (no clear of the whole first: l may be a ChainEnd's, just built).
    l.reflection = glm::vec3(0.0f);
    l.transmission = glm::vec3(0.0f);
    l.normal = normal;
    l.faceNormal = front ? hit.geometricNormal : -hit.geometricNormal;
    l.wo = wo;
    l.mirrorDirection = mirror;
    l.refractDirection = glm::vec3(0.0f);
    l.roughAlpha = 0;
    l.eta = 1;
    l.tint = glm::vec3(1.0f);
    setPhong(hit, l);  // l.brdf, and l.reflection for a mirror
}

float lobeWeight(const Lobes& l, Lobe lobe) {
    switch (lobe) {
        case Lobe::Diffuse:
            return meanComponent(l.brdf.kd);
        case Lobe::Glossy:
            return meanComponent(l.brdf.glossyAlbedo());
        case Lobe::Reflection:
            return meanComponent(l.reflection);
        case Lobe::Transmission:
            return meanComponent(l.transmission);
    }
    return 0;
}

namespace {

float lobeMaxWeight(const Lobes& l, Lobe lobe) {
    switch (lobe) {
        case Lobe::Diffuse:
            return maxComponent(l.brdf.kd);
        case Lobe::Glossy:
            return maxComponent(l.brdf.glossyAlbedo());
        case Lobe::Reflection:
            return maxComponent(l.reflection);
        case Lobe::Transmission:
            return maxComponent(l.transmission);
    }
    return 0;
}

bool chooseAmong(const Lobes& l, const Lobe* lobes, int count, float u, Lobe& lobe,
                 float& probability, bool roulette) {
    float weights[4], total = 0;
    int lastWithWeight = -1;
    for (int i = 0; i < count; ++i) {
        // Roulette survives by the largest channel, so that no channel's throughput grows: by
        // the mean, a red wall would multiply the red of the paths that survive it by 2.5, and
        // the rare long red paths would dominate the estimate (a heavy tail, measured +4 % in
        // the red of a closed red sphere of albedo 0.8 after 256 frames).
        weights[i] =
            std::max(0.0f, roulette ? lobeMaxWeight(l, lobes[i]) : lobeWeight(l, lobes[i]));
        total += weights[i];
        if (weights[i] > 0) lastWithWeight = i;
    }
    if (!(total > 0)) return false;
    // Under roulette the weights are the probabilities (the rest absorbs) unless they exceed 1.
    const float scale = roulette ? std::max(1.0f, total) : total;
    float edge = 0;
    for (int i = 0; i < count; ++i) {
        if (!(weights[i] > 0)) continue;
        edge += weights[i] / scale;
        if (u < edge) {
            lobe = lobes[i];
            probability = weights[i] / scale;
            return true;
        }
    }
    // The probabilities sum to one up to rounding: u above the last edge is the last lobe.
    if (roulette && scale == 1.0f && total < 1.0f) return false;  // absorbed
    lobe = lobes[lastWithWeight];
    probability = weights[lastWithWeight] / scale;
    return true;
}

}  // namespace

bool chooseLobe(const Lobes& l, float u, Lobe& lobe, float& probability, bool roulette) {
    static constexpr Lobe kAll[] = {Lobe::Diffuse, Lobe::Glossy, Lobe::Reflection,
                                    Lobe::Transmission};
    return chooseAmong(l, kAll, 4, u, lobe, probability, roulette);
}

bool chooseDeltaLobe(const Lobes& l, float u, Lobe& lobe, float& probability, bool roulette) {
    static constexpr Lobe kDelta[] = {Lobe::Reflection, Lobe::Transmission};
    return chooseAmong(l, kDelta, 2, u, lobe, probability, roulette);
}

float remapChoice(float u, float probability) {
    return probability > 0 ? std::min(u / probability, 0x1.fffffep-1f) : 0.0f;
}

glm::vec3 roughGlassValue(const Lobes& l, glm::vec3 wi) {
    const float cosFace = glm::dot(wi, l.faceNormal), cosN = glm::dot(wi, l.normal);
    if (cosFace * cosN <= 0) return glm::vec3(0.0f);  // the two normals disagree on its side
    const float f = roughdielectric::evaluate(l.roughAlpha, l.eta, l.normal, l.wo, wi);
    return cosN < 0 ? f * l.tint : glm::vec3(f);
}

float roughGlassPdf(const Lobes& l, glm::vec3 wi) {
    const float cosFace = glm::dot(wi, l.faceNormal), cosN = glm::dot(wi, l.normal);
    if (cosFace * cosN <= 0) return 0.0f;
    return roughdielectric::pdf(l.roughAlpha, l.eta, l.normal, l.wo, wi);
}

bool sampleLobe(const Lobes& l, Lobe lobe, glm::vec2 u, float uChoice, glm::vec3& direction,
                glm::vec3& weight) {
    switch (lobe) {
        case Lobe::Transmission:
            if (l.roughGlass()) {
                roughdielectric::Sample s;
                if (!roughdielectric::sample(l.roughAlpha, l.eta, l.normal, l.wo, u, uChoice, s))
                    return false;
                direction = s.wi;
                weight = s.refracted ? s.weight * l.tint : glm::vec3(s.weight);
                const float cosFace = glm::dot(direction, l.faceNormal);
                return s.refracted ? cosFace < 0 : cosFace > 0;
            }
            direction = l.refractDirection;
            weight = l.transmission;
            return glm::dot(direction, l.faceNormal) < 0;
        case Lobe::Reflection:
            direction = l.mirrorDirection;
            weight = l.reflection;
            return glm::dot(direction, l.faceNormal) > 0;
        case Lobe::Diffuse:
            direction = Frame(l.normal).toWorld(squareToCosineHemisphere(u));
            weight = l.brdf.kd;
            return glm::dot(direction, l.normal) > 0 && glm::dot(direction, l.faceNormal) > 0;
        case Lobe::Glossy: {
            if (l.brdf.model == GlossyModel::Ggx) {
                // By visible normals: f cos / pdf is F G2 / G1(wo), at most F.
                const float alpha = l.brdf.exponent;
                direction = ggx::sample(alpha, l.normal, l.wo, u);
                const float cosTheta = glm::dot(direction, l.normal);
                if (cosTheta <= 0 || glm::dot(direction, l.faceNormal) <= 0) return false;
                const float pdf = ggx::pdf(alpha, l.normal, direction, l.wo);
                if (!(pdf > 0)) return false;
                weight = l.brdf.glossy(direction) * (cosTheta / pdf);
                return isFinite(weight);
            }
            // Normalized Phong: f = Ks (n + 2) / (2 pi) cos^n(alpha), sampled with pdf
            // (n + 1) / (2 pi) cos^n(alpha) about the mirror direction, so f cos / pdf is below.
            direction = Frame(l.mirrorDirection).toWorld(squareToPhongLobe(u, l.brdf.exponent));
            const float cosTheta = glm::dot(direction, l.normal);
            if (cosTheta <= 0 || glm::dot(direction, l.faceNormal) <= 0) return false;
            weight = l.brdf.ks * ((l.brdf.exponent + 2.0f) / (l.brdf.exponent + 1.0f) * cosTheta);
            return true;
        }
    }
    return false;
}

}  // namespace igi
