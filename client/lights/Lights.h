#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "lights/EmissiveTexture.h"
#include "lights/LightTree.h"
#include "lights/Vpl.h"
#include "render/RenderSettings.h"
#include "sampling/Distribution1D.h"
#include "scene/Scene.h"
#include "tracing/SunDisk.h"
#include "tracing/TraceableScene.h"

namespace igi {

/// A point chosen on a light source.
///
/// An environment sample is an area-light sample on a sphere kSunDistance radii away, facing
/// the scene, whose area density gives the environment's solid-angle density there: receivers
/// connect to it (and weigh it against BRDF sampling) as to a point on a quad light.
///
/// A directional light's sample is a point light far outside the scene (kSunDistance radii
/// beyond its bounding sphere, in the sampled direction) whose intensity gives the sun's
/// irradiance at the scene: every receiver connects to it as to a point light, with a parallax
/// and a 1/d^2 variation across the scene below 2e-5. A soft sun's (one with an angle, whose
/// disk is visible) is an area-light sample on the far sphere instead, as the environment's,
/// so that glossy lobes weigh it against BRDF sampling. Light paths leave either from across
/// the scene instead (Lights::parallelStart), along `direction`.
struct LightSample {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f};   ///< emitting side of an area light; a spot light's axis
    glm::vec3 emitted{0.0f};  ///< radiance of an area light, intensity (W/sr) of a point light
                              ///< (on the axis for a spot)
    float pdf = 0;            ///< selection probability times 1/area (area lights), or selection
    float select = 0;         ///< the selection probability alone
    bool isPoint = false;     ///< point, spot or directional: a delta position
    bool spot = false;        ///< emitted times spotRamp(cosOuter, spotScale, cos to the axis)
    float cosOuter = -1.0f, spotScale = 0.0f;
    /// A directional light or the environment: parallel light from infinitely far away.
    bool directional = false;
    glm::vec3 direction{0.0f};  ///< directional: the way its light travels, as sampled
    /// Directional: on a plane facing `direction`, divided by the density of `direction` (for
    /// the environment: radiance over its solid-angle density).
    glm::vec3 irradiance{0.0f};
};

/// How far (in scene radii) past the scene a directional light's sample sits.
constexpr float kSunDistance = 1e5f;

/// Up to this many point, spot and sun lights in a scene are exact lights (Lights::exactLight):
/// each is one shadow ray of every receiving point, not chosen among the others. More, and
/// they are chosen with the rest (a shadow ray each per point would cost more than it saves).
constexpr std::size_t kMaxExactLights = 4;

/// Every light source of a scene: emissive triangles (from Ke materials and quad lights; zero-area
/// ones and those whose emissive texture is black there skipped, a face listed twice counted
/// once) and point lights. Light paths leave them by
/// emitted power; a point that receives light chooses them either by power too or, with many
/// lights, by what each could give it there (a LightTree), so that its few samples go to the
/// lights that matter to it.
///
/// Exact lights: when a scene has at most kMaxExactLights point, spot and sun lights, a
/// receiving point does not choose them; it sends one shadow ray to each (exactLight), and
/// chooses among the other lights only. A delta light's one sample is its exact light, so a
/// receiver's light from it is then the same in every set: the interleaved sets' neighbouring
/// pixels do not differ by how many of their samples it drew (with a sun and a sky, 3 or 4 of
/// 4: a tenth of the sunlight from pixel to pixel), which the discontinuity buffer would have
/// to average across shadow edges. Integrators keep that light out of the filtered irradiance.
class Lights {
  public:
    /// The emissive triangles of `traceable` (quad lights included) and the point lights that
    /// are on; `sampling` says how a receiving point chooses among them (Auto: the tree from
    /// kLightTreeMinLights lights on).
    Lights(const TraceableScene& traceable, const std::vector<PunctualLight>& punctualLights,
           LightSampling sampling = LightSampling::Power);

    bool empty() const { return distribution_.empty(); }
    std::size_t count() const { return emitters_.size(); }
    /// Whether sampleAt() chooses by the receiving point (the tree) rather than by power.
    bool choosesPerPoint() const { return !tree_.empty(); }

    /// Chooses a light with uSelect (by power) and a point on it with uPoint. `uRemapped`, if
    /// given, receives uSelect rescaled within the chosen light: a fresh uniform number.
    LightSample sample(float uSelect, glm::vec2 uPoint, float* uRemapped = nullptr) const;

    /// The same among the lights receivers choose (all but the exact lights), by power.
    LightSample sampleForReceivers(float uSelect, glm::vec2 uPoint) const;
    /// The same for light arriving at p (unit normal n, front side only): by the tree when
    /// choosesPerPoint(), else as sampleForReceivers(). Exact lights are never chosen.
    /// `memo` (for several samples at one p and n) saves weighing the tree's nodes again.
    LightSample sampleAt(glm::vec3 p, glm::vec3 n, float uSelect, glm::vec2 uPoint,
                         LightTree::Memo* memo = nullptr) const;

    /// How many exact lights there are, and the k-th's sample (selection 1; uPoint places it
    /// on a soft sun's disk).
    std::size_t exactLights() const { return exact_.size(); }
    LightSample exactLight(std::size_t k, glm::vec2 uPoint) const;
    /// Whether receivers have lights to choose among (besides the exact ones).
    bool receiversChoose() const { return !receivers_.empty(); }

    /// Area-measure density with which sampleAt(p, n) picks a point on the emissive triangle
    /// (mesh, triangle), for multiple importance sampling; 0 if it is not a light.
    float areaPdfAt(std::uint32_t mesh, std::uint32_t triangle, glm::vec3 p, glm::vec3 n) const;

    /// Calls f(a, b, c) with the corners of each emissive triangle.
    template <class F>
    void forEachTriangle(F&& f) const {
        for (const Emitter& e : emitters_)
            if (e.kind == Kind::Triangle) f(e.p0, e.p0 + e.e1, e.p0 + e.e2);
    }

    /// Total emitted power, summed luminance (for tests and statistics).
    double totalPower() const { return distribution_.total(); }
    /// Whether some light is directional (light paths then start at parallelStart).
    bool hasDirectional() const { return hasDirectional_; }
    /// The density (solid angle) with which sampleAt(p, n) picks the environment in the
    /// direction `toSky`, for multiple importance sampling; 0 without one.
    float environmentPdfAt(glm::vec3 p, glm::vec3 n, glm::vec3 toSky) const;
    /// Whether some light is a delta in position or direction (point, spot, a sun without an
    /// angle): one that only a light sample finds, never a sampled direction.
    bool hasDeltaLights() const { return hasDeltaLights_; }
    /// Whether some soft sun is on (its disk is seen in the sky: SunDisk).
    bool hasSuns() const { return !suns_.empty(); }
    /// The radiance of the suns' disks that a direction sampled from a BRDF at p (normal n)
    /// with solid-angle density `brdfPdf` sees along the unit `toSky`, each weighted by the
    /// power heuristic against the `lightSamples` light samples at p that could have chosen it
    /// (an exact sun: against its own one sample).
    glm::vec3 sunsSeenByBrdf(glm::vec3 p, glm::vec3 n, glm::vec3 toSky, float brdfPdf,
                             float lightSamples) const;

    /// Where a light path of a directional light travelling along unit `direction` starts: a
    /// point, uniform by u, on the disk of the scene's bounding sphere's radius that faces
    /// `direction`, just outside the sphere. Its area is diskArea().
    glm::vec3 diskOrigin(glm::vec3 direction, glm::vec2 u) const;
    float diskArea() const;

    /// Where a light path of a directional light or of the environment travelling along unit
    /// `direction` starts, and the area of the region it is uniform on.
    struct ParallelStart {
        glm::vec3 origin{0.0f};
        float area = 0;
    };
    /// The start of a parallel light path: uniform by u on the rectangle across `direction`
    /// that bounds the shadow of the scene's box along it (every line along `direction` that
    /// meets the scene crosses it), just outside the bounding sphere as diskOrigin's; on that
    /// disk where the rectangle is not smaller. In an elongated scene the disk of the bounding
    /// sphere is mostly empty: on the sunlit Sponza 43 % of the sun's paths from it hit nothing
    /// (the rectangle is 0.6 of the disk there), and the few VPLs of a set are shared by every
    /// pixel of the frame, so their noise does not average out over the image.
    ParallelStart parallelStart(glm::vec3 direction, glm::vec2 u) const;

  private:
    enum class Kind : std::uint8_t { Triangle, Point, Spot, Directional, Environment };
    struct Emitter {
        glm::vec3 p0{0.0f}, e1{0.0f}, e2{0.0f};  ///< triangle p0, p0+e1, p0+e2, or the point
        glm::vec3 normal{0.0f};   ///< a triangle's; a spot's axis; a directional light's direction
        glm::vec3 emitted{0.0f};  ///< radiance, intensity or (directional) irradiance
        float area = 0;
        /// A triangle's emissive texture: `emitted` (the material's emission) times its texel
        /// at the sampled point. Chosen by the texture's mean, the point uniform in area.
        EmissiveTexture texture;
        Kind kind = Kind::Triangle;
        float cosOuter = -1.0f, spotScale = 0.0f;  ///< spot: spotRamp's parameters
        /// Directional: 1 - cos of the disk's half-angle (0: a delta), and the factor from
        /// the irradiance to the estimate of one direction sampled uniformly in that cone.
        float oneMinusCos = 0.0f, sunScale = 1.0f;
        bool isPoint() const { return kind != Kind::Triangle && kind != Kind::Environment; }
    };

    LightSample pointOn(std::size_t emitter, float selection, glm::vec2 uPoint) const;
    /// The probability with which sampleAt(p, n) chooses `emitter` (0 for an exact light).
    float receiverSelection(glm::vec3 p, glm::vec3 n, std::uint32_t emitter) const;

    std::vector<Emitter> emitters_;
    Distribution1D distribution_;  ///< light paths' choice: every light
    Distribution1D receivers_;     ///< receivers' choice by power: every light but the exact ones
    std::vector<std::uint32_t> exact_;  ///< the exact lights' emitters
    LightTree tree_;  ///< empty when receivers choose by power; over the receivers' lights
    std::vector<std::uint32_t> treeEmitter_;  ///< the tree's light t is emitter treeEmitter_[t]
    /// An emitter's light in the tree, or kNotInTree (an exact light): a vector, not a map,
    /// since MIS weights look it up for every sampled direction that finds a light.
    static constexpr std::uint32_t kNotInTree = 0xFFFFFFFFu;
    std::vector<std::uint32_t> emitterTree_;
    std::unordered_map<std::uint64_t, std::uint32_t> triangleToEmitter_;
    /// A soft sun's disk and its emitter (for its selection probability), and whether it is
    /// an exact light (then its one sample is what BRDF sampling is weighed against).
    struct Sun {
        SunDisk disk;
        std::uint32_t emitter = 0;
        bool exact = false;
    };
    std::vector<Sun> suns_;
    const EnvironmentMap* environment_ = nullptr;  ///< when the scene has a sky
    std::uint32_t environmentIndex_ = 0;           ///< its emitter
    glm::vec3 center_{0.0f};                       ///< the scene's bounding sphere
    float radius_ = 1.0f;
    glm::vec3 boxLo_{0.0f}, boxHi_{0.0f};  ///< the scene's box, for parallelStart
    bool hasBox_ = false;
    bool hasDirectional_ = false;
    bool hasDeltaLights_ = false;
};

/// A light sample as the point light that one of `samples` direct-light shadow rays goes to: its
/// power is the sample's emission over its density and the count, its position lifted off the
/// light's surface (shadow rays end there).
Vpl directLightVpl(const LightSample& s, const TraceableScene& scene, int samples);

}  // namespace igi
