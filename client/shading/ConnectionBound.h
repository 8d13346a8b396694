#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace igi {

/// How the bound's distance term falls off inside dmin.
enum class BoundShape : std::uint8_t {
    /// Instant radiosity's clamp: G <= cos cos / dmin^2 (kept = d^2 / dmin^2 inside dmin).
    Clamp,
    /// Instant caching's bounded geometry term (paper 003, equations 2 and 3): the connection
    /// is kept whole beyond 1.2 dmin, dropped inside 0.8 dmin, and between the two by the
    /// smoothstep 3 t^2 - 2 t^3 of t = (d / dmin - 0.8) / 0.4.
    Smooth,
};

/// The bound on a VPL connection: instant radiosity's clamp and its glossy counterpart as one
/// rule. Of the connection between a point x and a VPL y at distance d, the fraction
///   kept = min(1, d^2 / (dmin^2 s_x s_y), S / s_x)
/// is added, where s_x and s_y are the sharpness of the two ends' BRDFs for this pair of
/// directions (SurfaceBrdf::sharpness: pi times the BRDF normalized to unit albedo, 1 for a
/// Lambertian surface, up to (n + 2) / 2 in a Phong peak) and S the sharpness budget (>= 1).
/// - Between Lambertian ends the first term is the clamp G <= cos cos / dmin^2 exactly (its
///   1 / d^2 spikes near creases); with a glossy end it starts farther out.
/// - The second bounds a glossy receiver at any distance: through a sharp lobe a few VPLs per
///   set would show as so many highlights. Only the receiver's lobe is bounded so: a glossy VPL
///   lighting a wall paints a soft blotch, while taking that light from the VPL would leave it
///   to the wall's continuation rays finding the lights in the glossy surface's lobe, one
///   firefly at a time.
/// Written in sharpness rather than in the BRDF itself, it depends on neither colour nor
/// texture; dmin is a fraction of the scene's diagonal, so it means the same at every scale.
/// The rest, 1 - kept, is what the Kollig-Keller compensation (EndPointShader) adds back by a
/// continuation ray sampled from the BRDF: for a sharp lobe that is most of the light, which is
/// what BRDF sampling is good at.
/// With BoundShape::Smooth the distance term is the paper 003's smoothstep of
/// d / (dmin sqrt(s_x s_y)) instead of the clamp's min(1, d^2 / (dmin^2 s_x s_y)).
struct ConnectionBound {
    /// d^2 / (dmin^2 s_x) and S / s_x: what the bound leaves of a connection ending on a
    /// surface of sharpness 1 is min(1, shape(distanceTerm), budgetTerm).
    float distanceTerm = 0;
    float budgetTerm = 0;
    BoundShape shape = BoundShape::Clamp;

    static ConnectionBound of(float distance2, float minDistance2, float sharpnessBudget,
                              float sharpnessX, BoundShape shape = BoundShape::Clamp) {
        const float s = atLeastLambertian(sharpnessX);
        return {distance2 / (minDistance2 * s), sharpnessBudget / s, shape};
    }
    float kept(float sharpnessY) const {
        const float t = distanceTerm / atLeastLambertian(sharpnessY);
        const float byDistance = shape == BoundShape::Smooth ? smoothKept(t) : std::min(1.0f, t);
        return std::min(std::min(1.0f, budgetTerm), byDistance);
    }
    /// Whether some far end of sharpness at most `maxSharpnessY` is not kept whole.
    bool cuts(float maxSharpnessY) const {
        return budgetTerm < 1.0f || distanceTerm < reach2(shape) * atLeastLambertian(maxSharpnessY);
    }
    /// (d / dmin)^2 beyond which a Lambertian connection is kept whole.
    static float reach2(BoundShape shape) { return shape == BoundShape::Smooth ? 1.44f : 1.0f; }
    /// The paper's f(0.8, 1.2, x) of x = sqrt(t), t = d^2 / (dmin^2 s_x s_y).
    static float smoothKept(float t) {
        if (t >= 1.44f) return 1.0f;
        if (t <= 0.64f) return 0.0f;
        const float u = (std::sqrt(t) - 0.8f) * 2.5f;
        return u * u * (3.0f - 2.0f * u);
    }
    /// A sharpness below 1 (the side of a glossy surface away from its lobe, where only its
    /// diffuse share reflects) counts as 1: it would pull the clamp closer than the Lambertian
    /// one, and the spike it lets through, bounded against the surface's whole albedo, is
    /// 1 / share times the diffuse lobe's own light (seen on CornellBox-Glossy: a light path
    /// bouncing in the crease between the glossy sphere and a wall left VPLs at 0.6 dmin from
    /// the sphere, 90 times the sphere's converged value there).
    static float atLeastLambertian(float sharpness) { return std::max(1.0f, sharpness); }
};

inline float keptFraction(float distance2, float minDistance2, float sharpnessBudget,
                          float sharpnessX, float sharpnessY,
                          BoundShape shape = BoundShape::Clamp) {
    return ConnectionBound::of(distance2, minDistance2, sharpnessBudget, sharpnessX, shape)
        .kept(sharpnessY);
}

/// Power heuristic (beta = 2) weight of a strategy of density `a` against one of density `b`
/// (each already multiplied by its number of samples). The two weights sum to one.
inline float powerHeuristic(float a, float b) {
    if (!(a > 0)) return 0.0f;
    const float a2 = a * a, b2 = b * b;
    return a2 / (a2 + b2);
}

}  // namespace igi
