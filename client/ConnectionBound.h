#pragma once

#include <algorithm>

namespace igi {

/// The bound on a VPL connection: instant radiosity's clamp and its glossy counterpart as one
/// rule. Of the connection between a point x and a VPL y at distance d, the fraction
///   kept = min(1, d^2 / (dmin^2 s_x s_y))
/// is added, where s_x and s_y are the sharpness of the two ends' BRDFs for this pair of
/// directions (SurfaceBrdf::sharpness: pi times the BRDF normalized to unit albedo). Between
/// Lambertian ends s = 1 and this is the clamp G <= cos cos / dmin^2 exactly; in a Phong peak
/// s = (n + 2) / 2 and the bound starts farther out, so a glossy VPL cannot spike either.
/// Written in sharpness rather than in the BRDF itself, it depends on neither colour nor
/// texture. dmin is a fraction of the scene's diagonal, so it means the same at every scale.
/// The rest, 1 - kept, is what the Kollig-Keller compensation (EndPointShader) adds back.
inline float keptFraction(float distance2, float minDistance2, float sharpnessX, float sharpnessY) {
    const float limit = minDistance2 * sharpnessX * sharpnessY;
    return distance2 >= limit ? 1.0f : distance2 / limit;
}

/// Power heuristic (beta = 2) weight of a strategy of density `a` against one of density `b`
/// (each already multiplied by its number of samples). The two weights sum to one.
inline float powerHeuristic(float a, float b) {
    if (!(a > 0)) return 0.0f;
    const float a2 = a * a, b2 = b * b;
    return a2 / (a2 + b2);
}

}  // namespace igi
