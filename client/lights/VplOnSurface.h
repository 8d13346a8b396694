#pragma once

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "lights/Vpl.h"
#include "math/Color.h"
#include "shading/Scattering.h"
#include "tracing/SurfacePoint.h"

namespace igi {

/// The VPL where a light path carrying `flux` met a non-delta surface (`lobes` seen from the
/// direction the light came from): it carries the surface's BRDF. Its position is the caller's
/// (moved off the surface). On a normal- or bump-mapped surface it keeps the map's normal and
/// the geometric one, and bends the former toward each receiver (Vpl::bends).
inline Vpl vplOnSurface(const SurfacePoint& hit, const Lobes& lobes, glm::vec3 flux) {
    const SurfaceBrdf& b = lobes.brdf;
    Vpl v;
    v.position = hit.position;
    v.normal = lobes.normal;
    if (hit.material->perturbsNormal()) {
        v.bends = true;
        v.face = lobes.faceNormal;
        v.mapped = glm::dot(lobes.faceNormal, hit.geometricNormal) >= 0 ? hit.shadingNormal
                                                                        : -hit.shadingNormal;
    }
    v.power = flux * b.kd * kInvPi;
    v.diffuseShare = b.diffuseShare;
    v.glossyShare = b.glossyShare;
    if (b.hasGlossy() && b.model == GlossyModel::Ggx) {
        v.ggx = true;
        v.glossyPower = flux;
        v.exponent = b.exponent;  // alpha
        v.f0 = b.ks;
        v.mirror = lobes.mirrorDirection;  // lobes.wo, where the light came from, mirrored
    } else if (b.hasGlossy()) {
        v.glossyPower = flux * b.ks * ((b.exponent + 2.0f) * 0.5f * kInvPi);
        v.exponent = b.exponent;
        v.mirror = lobes.mirrorDirection;  // lobes.wo is where the light came from
    }
    return v;
}

}  // namespace igi
