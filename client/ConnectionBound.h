#pragma once

#include <algorithm>

namespace igi {

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
struct ConnectionBound {
    /// min(d^2 / (dmin^2 s_x), S / s_x): what the bound leaves of a connection ending on a
    /// surface of sharpness 1; kept = min(1, distanceTerm / s_y, budgetTerm).
    float distanceTerm = 0;
    float budgetTerm = 0;

    static ConnectionBound of(float distance2, float minDistance2, float sharpnessBudget,
                              float sharpnessX) {
        const float s = atLeastLambertian(sharpnessX);
        return {distance2 / (minDistance2 * s), sharpnessBudget / s};
    }
    float kept(float sharpnessY) const {
        const float s = atLeastLambertian(sharpnessY);
        const float byDistance = distanceTerm >= s ? 1.0f : distanceTerm / s;
        return std::min(std::min(1.0f, budgetTerm), byDistance);
    }
    /// Whether some far end of sharpness at most `maxSharpnessY` is not kept whole.
    bool cuts(float maxSharpnessY) const {
        return budgetTerm < 1.0f || distanceTerm < atLeastLambertian(maxSharpnessY);
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
                          float sharpnessX, float sharpnessY) {
    return ConnectionBound::of(distance2, minDistance2, sharpnessBudget, sharpnessX)
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
