#pragma once

#include <memory>

#include <cstdint>
#include <optional>
#include <vector>

#include "integrators/EndPointShader.h"
#include "integrators/LightEdges.h"
#include "integrators/PathRandom.h"
#include "integrators/PixelResult.h"
#include "integrators/PixelSampler.h"
#include "integrators/RoughGlassLight.h"
#include "lighting/LightingSet.h"
#include "lights/Lights.h"
#include "render/RenderSettings.h"
#include "scene/CameraModel.h"
#include "shading/DeltaChain.h"
#include "tracing/TraceableScene.h"

namespace igi {

/// Instant Global Illumination at one pixel (paper, section 4): one eye path, split at its
/// first hit into its non-delta part (Lambertian and glossy, shaded there) and one path per
/// delta component (mirror, glass), followed to a non-delta end point. Each end point is
/// shaded by the EndPointShader with the pixel's set. The end point of largest reflectance is
/// the one the master filters (its irradiance and its glossy radiance); the others are sent as
/// unfiltered radiance, with every light seen directly or through mirrors and glass.
class IgiIntegrator {
  public:
    IgiIntegrator(const TraceableScene& scene, const Lights& lights, const RenderSettings& settings,
                  const CameraModel& camera);
    /// Renders `other`'s scene, lights and camera with `settings`, sharing its pixels at light
    /// edges (a function of the lights and the camera only) where both gather there
    /// (TileRenderer's first frame, whose settings differ in samples and VPLs only).
    IgiIntegrator(const IgiIntegrator& other, const RenderSettings& settings);

    /// A pixel to shade: where it is in the image and its index (y * width + x).
    struct Pixel {
        int x = 0, y = 0;
        std::uint32_t index = 0;
    };

    PixelResult shade(int x, int y, std::uint32_t pixelIndex, std::uint32_t frame,
                      const LightingSet& set, RayCounters& counters) const;
    /// Shades `count` pixels of one set into results[0, count): each exactly as shade() would,
    /// their rays traced together (eye rays in packets, shadow rays in packets by target through
    /// a ShadowQueue), which is faster. The result of a pixel does not depend on the others.
    void shade(const Pixel* pixels, int count, std::uint32_t frame, const LightingSet& set,
               PixelResult* results, RayCounters& counters) const;

    /// E / pi at a Lambertian point lit by `set`, with `normal` facing the viewer, without any
    /// continuation ray (public for tests).
    glm::vec3 irradianceOverPi(glm::vec3 position, glm::vec3 normal, glm::vec3 faceNormal,
                               const LightingSet& set, RayCounters& counters) const;

  private:
    struct PixelPath;
    struct Continuation;
    void traceEyeRays(PixelPath* paths, int count, RayCounters& counters) const;
    /// At the pixels of lightEdges_, the light seen directly (emitters and sky) from
    /// settings_.lightEdgeRays rays of their own, into the results' unfiltered radiance, in
    /// place of what the eye ray's own hit sees (RenderSettings::lightEdgeRays).
    void gatherLightAtEdges(const Pixel* pixels, int count, std::uint32_t frame, PixelPath* paths,
                            PixelResult* results, RayCounters& counters) const;
    /// The light an eye ray along `direction` sees directly: its hit's emission, or the sky.
    glm::vec3 seenDirectly(bool found, const SurfacePoint& hit, glm::vec3 direction) const;
    void traceContinuations(std::vector<Continuation>& rays, RayCounters& counters) const;
    /// Rays ray(0 .. count - 1) (origin, direction), traced in packets of the scene's width;
    /// land(k, found, hit) takes each one's result, filled as `detail` asks.
    template <class Ray, class Land>
    void traceInPackets(int count, Ray&& ray, Land&& land, RayCounters& counters,
                        TraceableScene::HitDetail detail = TraceableScene::HitDetail::Full) const;
    /// The first hit's emission, its non-delta end point, and the rays that leave it along its
    /// mirror and glass lobes (appended to `continuations`); on rough glass, the light of
    /// delta lights through it (roughGlassDeltaLight).
    void splitAtFirstHit(PixelPath& path, int pixel, PixelResult& result,
                         std::vector<Continuation>& continuations, RayCounters& counters) const;
    /// The pixel's mirror and glass paths from where their first rays landed (continuations
    /// from `next` on, advanced past the pixel's), then the end point the master filters.
    void followChains(PixelPath& path, int pixel, const std::vector<Continuation>& continuations,
                      std::size_t& next, PixelResult& result, RayCounters& counters) const;
    void shadeEnds(PixelPath& path, const LightingSet& set, const ShadowQueue& queue,
                   PixelResult& result, RayCounters& counters) const;

    /// What point, spot and sun lights (deltas, which no sampled direction hits) send through
    /// rough glass at `hit` toward the eye, by one light sample on the pixel's numbers: the
    /// continuation, sampled from the BSDF, carries every other light.
    glm::vec3 roughGlassDeltaLight(const SurfacePoint& hit, const Lobes& lobes, PathRandom& random,
                                   RayCounters& counters) const;

    const TraceableScene& scene_;
    const Lights& lights_;
    RenderSettings settings_;
    const CameraModel& camera_;
    EndPointShader shader_;
    /// Where gatherLightAtEdges works (empty: lightEdgeRays 0); never null.
    std::shared_ptr<const LightEdges> lightEdges_;
};

}  // namespace igi
