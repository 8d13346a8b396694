#pragma once
// Tangent-space normal maps (glTF normalTexture) and the shading normal's below-surface fix.

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat2x2.hpp>
#include <glm/matrix.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace igi::normalmap {

/// A tangent frame about a unit normal n: t toward +u, b toward +v (igi's v, up in the image),
/// both unit and orthogonal to n.
struct TangentFrame {
    glm::vec3 tangent{0.0f};
    glm::vec3 bitangent{0.0f};
};

namespace detail {
inline bool finite(glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
}  // namespace detail

/// The frame of an interpolated vertex tangent (glTF TANGENT, in the normal's space): the
/// tangent made orthogonal to n, the bitangent cross(n, tangent) * sign (the specification's).
/// False when the tangent is zero, parallel to n or not finite.
inline bool frameFromTangent(glm::vec3 n, glm::vec3 tangent, float sign, TangentFrame& frame) {
    const glm::vec3 t = tangent - n * glm::dot(n, tangent);
    const float len = glm::length(t);
    if (!(len > 1e-6f * glm::length(tangent)) || !std::isfinite(len)) return false;
    frame.tangent = t / len;
    frame.bitangent = glm::cross(n, frame.tangent) * (sign < 0 ? -1.0f : 1.0f);
    return detail::finite(frame.tangent) && detail::finite(frame.bitangent);
}

/// The frame of a triangle's uv derivatives: dp/du made orthogonal to n (Gram-Schmidt), and
/// cross(n, tangent) on the side of dp/dv. One frame per triangle, from igi's uvs (v up the
/// image, as glTF's green): unlike MikkTSpace, which the glTF specification asks for when a
/// mesh has no TANGENT, nothing is averaged over the triangles that share a vertex, so the
/// frame jumps at every edge where the uv mapping bends, and a triangle whose uvs are mirrored
/// gets its own handedness rather than the one of the vertices it shares (seams of mirrored
/// halves differ). False for degenerate uvs (a triangle whose uvs have no area) or positions.
inline bool frameFromUvs(glm::vec3 n, const glm::vec3 p[3], const glm::vec2 uv[3],
                         TangentFrame& frame) {
    const glm::vec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
    const glm::vec2 d1 = uv[1] - uv[0], d2 = uv[2] - uv[0];
    const float det = d1.x * d2.y - d2.x * d1.y;
    // Relative to the uvs' extent: a sliver of uv space is as good as none.
    const float extent = std::max(glm::dot(d1, d1), glm::dot(d2, d2));
    if (!(std::abs(det) > 1e-7f * extent) || !std::isfinite(det)) return false;
    const glm::vec3 dpdu = (d2.y * e1 - d1.y * e2) / det;
    const glm::vec3 dpdv = (d1.x * e2 - d2.x * e1) / det;
    if (!detail::finite(dpdu) || !detail::finite(dpdv)) return false;
    const glm::vec3 t = dpdu - n * glm::dot(n, dpdu);
    const float len = glm::length(t);
    if (!(len > 1e-6f * glm::length(dpdu)) || !std::isfinite(len)) return false;
    frame.tangent = t / len;
    const glm::vec3 b = glm::cross(n, frame.tangent);
    frame.bitangent = glm::dot(b, dpdv) < 0 ? -b : b;
    return detail::finite(frame.bitangent);
}

/// The frame of a map looked up at uv' = linear * uv + offset (KHR_texture_transform), from
/// `frame`, the one of uv: tangent and bitangent along d p / d u' and d p / d v', each the frame
/// times a column of the inverse of `linear`, made unit (the bitangent kept orthogonal to the
/// tangent, on its side). False when `linear` is singular.
inline bool transformFrame(const glm::mat2& linear, TangentFrame& frame) {
    const float det = linear[0][0] * linear[1][1] - linear[1][0] * linear[0][1];
    if (!(std::abs(det) > 0) || !std::isfinite(det)) return false;
    const glm::mat2 inverse = glm::inverse(linear);
    const glm::vec3 t = inverse[0].x * frame.tangent + inverse[0].y * frame.bitangent;
    const glm::vec3 b = inverse[1].x * frame.tangent + inverse[1].y * frame.bitangent;
    const float tLen = glm::length(t);
    if (!(tLen > 0) || !std::isfinite(tLen)) return false;
    const glm::vec3 tangent = t / tLen;
    const glm::vec3 bOrtho = b - tangent * glm::dot(tangent, b);
    const float bLen = glm::length(bOrtho);
    if (!(bLen > 0) || !std::isfinite(bLen)) return false;
    frame.tangent = tangent;
    frame.bitangent = bOrtho / bLen;
    return true;
}

/// The tangent-space normal of a texel of a linear normal map: 2 texel - 1, its x and y
/// scaled by glTF's normalTexture.scale (+x toward +u, +y toward +v, +z along the normal).
inline glm::vec3 tangentSpaceNormal(glm::vec3 texel, float scale) {
    const glm::vec3 n = 2.0f * texel - 1.0f;
    return {n.x * scale, n.y * scale, n.z};
}

/// The normal of tangent-space `local` in the frame about n, unit; n itself when that has no
/// length or is not finite.
inline glm::vec3 perturb(glm::vec3 n, const TangentFrame& frame, glm::vec3 local) {
    const glm::vec3 w = local.x * frame.tangent + local.y * frame.bitangent + local.z * n;
    const float len = glm::length(w);
    if (!(len > 0) || !std::isfinite(len)) return n;
    return w / len;
}

/// Cycles' ensure_valid_reflection (Blender): returns the shading normal n, bent toward the
/// geometric normal ng in the plane of the two just enough that the mirror direction of wo about it
/// lies above the geometric surface by min(0.9 ng.wo, 0.01); then wo is above it too, so no lobe
/// about it is black or sampled below. n unchanged when its mirror direction is above already; ng
/// when no bend does it. All on the side of ng that wo is on (ng.wo >= 0).
inline glm::vec3 ensureValidReflection(glm::vec3 ng, glm::vec3 wo, glm::vec3 n) {
    const glm::vec3 r = 2.0f * glm::dot(n, wo) * n - wo;
    const float threshold = std::min(0.9f * glm::dot(ng, wo), 0.01f);
    if (glm::dot(ng, r) >= threshold) return n;
    // A frame with ng as z and n in the x-z plane.
    const glm::vec3 xAxis = n - glm::dot(n, ng) * ng;
    const float xLen = glm::length(xAxis);
    if (!(xLen > 1e-7f) || !std::isfinite(xLen)) return ng;
    const glm::vec3 x = xAxis / xLen;
    // Solve 2 (n'.wo) n'.z - wo.z = threshold for n' = (sqrt(1 - z^2), 0, z), in double:
    // near grazing views the two terms of z^2 cancel to a few float digits.
    const double ix = glm::dot(wo, x), iz = glm::dot(wo, ng), t = threshold;
    const double ix2 = ix * ix, iz2 = iz * iz;
    const double a = ix2 + iz2;
    if (!(a > 0)) return ng;
    const double b = std::sqrt(std::max(0.0, ix2 * (a - t * t)));
    const double c = iz * t + a;
    const double fac = 0.5 / a;
    const double z1 = fac * (b + c), z2 = fac * (-b + c);
    bool valid1 = z1 > 1e-5 && z1 <= 1.0 + 1e-5;
    bool valid2 = z2 > 1e-5 && z2 <= 1.0 + 1e-5;
    auto normalOf = [](double zz) {
        return glm::dvec2(std::sqrt(std::max(0.0, 1.0 - zz)), std::sqrt(std::max(0.0, zz)));
    };
    glm::dvec2 chosen;
    if (valid1 && valid2) {
        const glm::dvec2 n1 = normalOf(z1), n2 = normalOf(z2);
        const double r1 = 2.0 * (n1.x * ix + n1.y * iz) * n1.y - iz;
        const double r2 = 2.0 * (n2.x * ix + n2.y * iz) * n2.y - iz;
        valid1 = r1 >= 1e-5;
        valid2 = r2 >= 1e-5;
        if (valid1 && valid2)
            chosen = r1 < r2 ? n1 : n2;  // the shallower reflection: the smaller bend
        else
            chosen = r1 > r2 ? n1 : n2;
    } else if (valid1 || valid2) {
        chosen = normalOf(valid1 ? z1 : z2);
    } else {
        return ng;
    }
    const glm::vec3 bent = glm::normalize(float(chosen.x) * x + float(chosen.y) * ng);
    // Whatever rounding left, wo and its mirror direction end above the surface: ng has both.
    if (!detail::finite(bent) || !(glm::dot(bent, wo) > 0) ||
        !(glm::dot(2.0f * glm::dot(bent, wo) * bent - wo, ng) >= 0))
        return ng;
    return bent;
}

}  // namespace igi::normalmap
