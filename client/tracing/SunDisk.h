#pragma once

#include <cmath>
#include <optional>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vec3.hpp>

#include "math/Warp.h"
#include "scene/Light.h"

namespace igi {

/// 1 - cos of the half-angle of a sun of angular diameter `angleDeg` (0: a delta), from the
/// sine, which keeps its digits for the real sun's 0.27 degrees.
inline float sunOneMinusCos(float angleDeg) {
    const float half = 0.5f * glm::radians(angleDeg);
    return 2.0f * std::sin(0.5f * half) * std::sin(0.5f * half);
}

/// A soft sun of irradiance E is a disk of constant radiance L with E = L pi sin^2(half), and
/// a direction uniform in the disk's cone estimates E as L * solid angle = E * 2 (1 - cos) /
/// sin^2 = E * 2 / (1 + cos): this factor.
inline float sunConeScale(float oneMinusCos) {
    return 2.0f / (2.0f - oneMinusCos);
}

/// The solid angle of a disk whose half-angle has this 1 - cos.
inline float sunSolidAngle(float oneMinusCos) {
    return 2.0f * kPi * oneMinusCos;
}

/// The disk a soft sun (a directional light with an angular diameter) is seen as in the sky:
/// camera rays, mirrors and glossy lobes that leave the scene toward it see its radiance. Its
/// radiance is the one its light samples imply (Lights: E times sunConeScale over the solid
/// angle, which is E / (pi sin^2 half)), so that seeing the disk and sampling it are one light.
/// A delta sun (angle 0) has no disk: it stays invisible, as a point light does.
struct SunDisk {
    glm::vec3 toSun{0.0f, 1.0f, 0.0f};  ///< unit, toward the disk's centre
    float oneMinusCos = 0.0f;           ///< of the half-angle
    glm::vec3 radiance{0.0f};

    float solidAngle() const { return sunSolidAngle(oneMinusCos); }
    /// Whether the unit direction `toSky` points into the disk: by the chord, |a - b|^2 = 2 (1 -
    /// cos), which keeps its digits where 1 - cos is 1e-5 (a dot product near 1 would not).
    bool contains(glm::vec3 toSky) const {
        const glm::vec3 chord = toSky - toSun;
        return glm::dot(chord, chord) <= 2.0f * oneMinusCos;
    }
};

/// The disk of a light that is a soft sun and on; none for any other light.
inline std::optional<SunDisk> sunDiskOf(const PunctualLight& l) {
    if (!l.on || l.kind != LightKind::Directional || !(l.angleDeg > 0.0f)) return std::nullopt;
    SunDisk d;
    d.toSun = -l.direction;
    d.oneMinusCos = sunOneMinusCos(l.angleDeg);
    if (!(d.oneMinusCos > 0.0f)) return std::nullopt;  // below float's reach: a delta
    d.radiance = l.intensity * (sunConeScale(d.oneMinusCos) / d.solidAngle());
    return d;
}

/// The disks of the soft suns among `lights`, in their order.
inline std::vector<SunDisk> sunDisksOf(const std::vector<PunctualLight>& lights) {
    std::vector<SunDisk> disks;
    for (const PunctualLight& l : lights)
        if (const std::optional<SunDisk> d = sunDiskOf(l)) disks.push_back(*d);
    return disks;
}

/// The radiance of every disk of `disks` that the unit direction `toSky` points into.
inline glm::vec3 sunRadianceToward(const std::vector<SunDisk>& disks, glm::vec3 toSky) {
    glm::vec3 sum(0.0f);
    for (const SunDisk& d : disks)
        if (d.contains(toSky)) sum += d.radiance;
    return sum;
}

}  // namespace igi
