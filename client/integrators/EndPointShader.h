#pragma once

#include <glm/vec3.hpp>

#include "integrators/PathRandom.h"
#include "lighting/LightingSet.h"
#include "lights/Lights.h"
#include "render/RenderSettings.h"
#include "shading/ConnectionBound.h"
#include "shading/Scattering.h"
#include "shading/ShadowQueue.h"
#include "tracing/TraceableScene.h"

namespace igi {

/// A non-delta surface point to shade, seen from direction wo.
struct ShadingPoint {
    glm::vec3 position{0.0f};
    glm::vec3 faceNormal{0.0f};  ///< geometric normal on the viewer's side
    SurfaceBrdf brdf;            ///< oriented to the viewer's side
    glm::vec3 wo{0.0f};          ///< toward the viewer
    glm::vec3 mirror{0.0f};      ///< wo mirrored about brdf.normal

    static ShadingPoint at(const SurfacePoint& hit, const Lobes& lobes) {
        return {hit.position, lobes.faceNormal, lobes.brdf, lobes.wo, lobes.mirrorDirection};
    }
};

/// What a point sends toward its viewer, split the way the master filters it.
struct EndPointLight {
    glm::vec3 irradiance{0.0f};  ///< E / pi as the Lambertian lobe sees it (times kd: radiance)
    glm::vec3 glossy{0.0f};      ///< radiance reflected by the Phong lobe
    /// The exact lights' part (LightingSet::exact), apart from the two above: the same in
    /// every set, so the master need not filter it (the primary point's goes unfiltered).
    glm::vec3 sharpIrradiance{0.0f};  ///< E / pi
    glm::vec3 sharpGlossy{0.0f};

    /// All the light the point sends toward the eye.
    glm::vec3 radiance(const SurfaceBrdf& brdf) const {
        return brdf.kd * (irradiance + sharpIrradiance) + glossy + sharpGlossy;
    }
    /// The exact lights' part of radiance().
    glm::vec3 sharpRadiance(const SurfaceBrdf& brdf) const {
        return brdf.kd * sharpIrradiance + sharpGlossy;
    }
};

/// Shades the end point of an eye path (and the points its continuations reach) with the
/// light of one set (docs/ACCURACY.md, "The estimator"):
/// - the set's light samples, through the whole BRDF; for a glossy lobe, weighted by multiple
///   importance sampling against the continuation below (Veach's power heuristic);
/// - its VPLs, through the whole BRDF at both ends, each connection bounded (ConnectionBound);
/// - its caustic photons (light that came through mirrors and glass);
/// - one continuation ray, sampled from the BRDF, for three things no VPL can give: the light
///   the bound removed, restored by Kollig and Keller's compensation (the point it reaches is
///   shaded the same way, with only the removed part of each connection, recursively); for a
///   glossy lobe, the lights it sees (the other half of the MIS pair) and the mirrors and glass
///   it sees, followed to their next non-delta point. Without a glossy lobe and without
///   compensation there is no continuation; without compensation it ends at once beyond the
///   bound's reach.
/// The continuation's random numbers come from the pixel's own sampler, so the result is a
/// function of the pixel, the frame and the set only.
class EndPointShader {
  public:
    EndPointShader(const TraceableScene& scene, const Lights& lights,
                   const RenderSettings& settings);

    EndPointLight shade(const ShadingPoint& x, const LightingSet& set, PathRandom& random,
                        RayCounters& counters) const {
        return shadeAt(x, set, &random, 0, nullptr, counters);
    }
    /// The same without any continuation ray: a deterministic function of the point and the
    /// set (for tests).
    EndPointLight shadeWithoutContinuation(const ShadingPoint& x, const LightingSet& set,
                                           RayCounters& counters) const {
        return shadeAt(x, set, nullptr, 0, nullptr, counters);
    }

    /// shade() in two steps, for many points at once: queue() puts a point's shadow rays to the
    /// set's lights and VPLs into `queue` without tracing them; once the queue is traced,
    /// finish() adds up what reached the point and the rest of its light (photons, the
    /// continuation). finish(queue(x)) after tracing gives exactly shade(x).
    struct Pending {
        std::uint32_t point = 0;          ///< the point's index in the queue
        bool continuation = false;        ///< whether finish() traces a continuation
        bool indirectFromMethod = false;  ///< Lambertian indirect light from the method's records
        std::uint32_t exactEntries = 0;   ///< its first queued connections: to exact lights
    };
    /// Written into `pending` (not returned: GCC packs a returned Pending into registers
    /// through the stack, and the 8-byte loads of the 4- and 1-byte stores wait for them).
    void queue(const ShadingPoint& x, const LightingSet& set, ShadowQueue& queue,
               Pending& pending) const {
        queueAt(x, set, true, 0, nullptr, queue, pending);
    }
    EndPointLight finish(const ShadingPoint& x, const LightingSet& set, PathRandom& random,
                         const Pending& pending, const ShadowQueue& queue,
                         RayCounters& counters) const {
        return finishAt(x, set, &random, 0, nullptr, pending, queue, counters);
    }

    /// Continuations nest at most this deep (compensation of a compensation, a glossy lobe's
    /// view of a glossy surface, ...); past it the deeper terms are left out.
    static constexpr int kMaxDepth = 3;

  private:
    struct Sums {
        glm::vec3 irradiance{0.0f};  ///< E (divided by pi at the end)
        glm::vec3 glossy{0.0f};
    };

    /// With a `residual` only the part that this bound removed from the connection by which
    /// this point was reached is added: each incoming direction w weighs
    /// 1 - residual->kept(s(w)), s this point's sharpness (ConnectionBound).
    EndPointLight shadeAt(const ShadingPoint& x, const LightingSet& set, PathRandom* random,
                          int depth, const ConnectionBound* residual, RayCounters& counters) const;
    void queueAt(const ShadingPoint& x, const LightingSet& set, bool withRandom, int depth,
                 const ConnectionBound* residual, ShadowQueue& queue, Pending& pending) const;
    EndPointLight finishAt(const ShadingPoint& x, const LightingSet& set, PathRandom* random,
                           int depth, const ConnectionBound* residual, const Pending& pending,
                           const ShadowQueue& queue, RayCounters& counters) const;
    /// Queues the connections to the set's light samples and VPLs. True when the method's
    /// records give the Lambertian indirect light instead of the VPLs.
    bool queueConnections(const ShadingPoint& x, const LightingSet& set, bool misWithContinuation,
                          const ConnectionBound* residual, ShadowQueue& queue) const;
    /// The connection to a light sample v (the set's target `target`), one of `lightSamples`
    /// at x; for a glossy lobe weighted by MIS against the continuation when `mis`.
    [[gnu::always_inline]] inline void connectLight(const ShadingPoint& x, const Vpl& v,
                                                    std::uint32_t target, float lightSamples,
                                                    bool mis, glm::vec3 origin,
                                                    const ConnectionBound* residual,
                                                    ShadowQueue& queue) const;
    /// The connection to the set's indirect VPL j, its contribution scaled by `scale` (a chosen
    /// VPL's weight), from the shadow rays' `origin` at x.
    void connectVpl(const ShadingPoint& x, const LightingSet& set, std::size_t j, float scale,
                    glm::vec3 origin, const ConnectionBound* residual, ShadowQueue& queue) const;
    /// Every VPL of the set at a Lambertian point under the paper's clamp: connectVpl's
    /// arithmetic four VPLs at a time, with the same result.
    void connectLambertian(const ShadingPoint& x, const LightingSet& set, glm::vec3 origin,
                           ShadowQueue& queue) const;
    /// This thread's queue for the points of one continuation depth, emptied.
    static ShadowQueue& scratchQueue(int depth);
    void gatherPhotons(const ShadingPoint& x, const LightingSet& set, bool withGlossy,
                       const ConnectionBound* residual, Sums& sums) const;
    void continueFrom(const ShadingPoint& x, const LightingSet& set, PathRandom& random, int depth,
                      const ConnectionBound* residual, Sums& sums, RayCounters& counters) const;

    const TraceableScene& scene_;
    const Lights& lights_;
    int directSamples_;
    int maxEyeDepth_;
    bool compensate_;
    /// The largest sharpness of any material: how far a compensation can reach.
    float maxSharpness_ = 1.0f;
};

}  // namespace igi
