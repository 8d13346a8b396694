#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "igi/CausticPhoton.h"
#include "lights/Lights.h"
#include "lights/Vpl.h"
#include "render/RenderSettings.h"
#include "tracing/TraceableScene.h"

namespace igi {

/// Shoots caustic photons at the mirrors and glass of a scene and follows them through delta
/// bounces to the first non-delta surface (paper, section 4.1), where they are stored. Photons
/// are aimed at the bounding spheres of the specular objects, so none is wasted on surfaces that
/// the light samples and VPLs light anyway; a scene without mirrors or glass has no target and
/// shoots none. They start on the lights (light-specular-diffuse paths: caustics) and, for the
/// converging estimator, on the VPLs (diffuse-specular-diffuse paths: a wall lighting the floor
/// through a mirror or a glass ball, which no VPL connection can carry).
class CausticShooter {
  public:
    CausticShooter(const TraceableScene& scene, const Lights& lights,
                   const RenderSettings& settings);

    /// Whether this scene needs caustic photons at all.
    bool active() const { return !targets_.empty() && !lights_.empty() && photons_ > 0; }

    /// The photons of set `setIndex` in `frame`; `shot` receives how many were emitted.
    std::vector<CausticPhoton> shoot(std::uint32_t frame, std::uint32_t setIndex,
                                     std::uint32_t& shot, RayCounters& counters) const;

    /// Adds to `out` the photons of `count` paths that start on the VPLs of set `setIndex` (one
    /// chosen uniformly per path, emitting through its BRDF); `shot` grows by the paths shot.
    void shootFromVpls(std::uint32_t frame, std::uint32_t setIndex, const std::vector<Vpl>& vpls,
                       std::uint32_t count, std::vector<CausticPhoton>& out, std::uint32_t& shot,
                       RayCounters& counters) const;
    /// Gathering radius in world units.
    float radius() const { return radius_; }

  private:
    struct Target {
        glm::vec3 center;
        float radius;
    };
    /// Density (solid angle) with which the target mixture picks `direction` from `origin`.
    float directionPdf(glm::vec3 origin, glm::vec3 direction) const;
    bool samplePhotonDirection(glm::vec3 origin, float uTarget, glm::vec2 u, glm::vec3& direction,
                               float& pdf) const;
    /// For parallel light along unit `direction`: a start on the disk that a chosen target's
    /// sphere casts on the plane across `direction` just outside the scene, and the area
    /// density of the target mixture there (the disks may overlap).
    bool sampleParallelOrigin(glm::vec3 direction, float uTarget, glm::vec2 u, glm::vec3& origin,
                              float& pdf) const;
    void trace(glm::vec3 origin, glm::vec3 direction, glm::vec3 power, std::uint32_t path,
               const class LightPathSampler& sampler, std::vector<CausticPhoton>& out,
               RayCounters& counters) const;

    const TraceableScene& scene_;
    const Lights& lights_;
    std::uint64_t seed_;
    std::uint32_t photons_;
    std::uint32_t maxDepth_;
    float radius_;
    std::vector<Target> targets_;
};

}  // namespace igi
