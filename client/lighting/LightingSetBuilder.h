#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>

#include "lighting/CausticShooter.h"
#include "lighting/LightingSet.h"
#include "lights/Lights.h"
#include "render/RenderSettings.h"
#include "sampling/LightPathNumbers.h"
#include "sampling/Scramble.h"
#include "tracing/TraceableScene.h"

namespace igi {

/// Builds the set P_k and C_k of one interleaving identification k in one frame: direct-light
/// samples on the lights, VPLs from quasi-random walks (Keller's instant radiosity), caustic
/// photons from the lights and from the VPLs. Deterministic in (seed, frame, accumulation, k):
/// every client builds the same set.
class LightingSetBuilder {
  public:
    LightingSetBuilder(const TraceableScene& scene, const Lights& lights,
                       const RenderSettings& settings);
    const TraceableScene& scene() const { return scene_; }

    /// The set of k = setIndex in `frame`, the frame's place in its accumulation being
    /// `accumulation` (TileAssign::accumulation: it shrinks the progressive radii).
    LightingSet build(std::uint32_t frame, std::uint32_t accumulation,
                      std::uint32_t setIndex) const;
    LightingSet build(std::uint32_t frame, std::uint32_t setIndex) const {
        return build(frame, 0, setIndex);
    }

    /// Light paths per set: settings.vplPaths, or derived from settings.indirectVpls.
    std::uint32_t vplPaths() const { return vplPaths_; }
    /// Paths still walking after d non-delta bounces in the paper's walk
    /// (d = 0 .. maxLightPathLength - 2); with roulette, those of the last go on by roulette.
    std::uint32_t survivors(std::uint32_t diffuseBounces) const;
    bool causticsActive() const { return caustics_.active(); }
    /// The most vertices a light path can have (the light's included), with or without roulette.
    int maxLightPathLength(bool roulette) const;

    /// The share of the points without a glossy lobe that trace the compensation ray in the
    /// frames after the first (the others add nothing, the tracers 1 / share times as much):
    /// it restores about 1 % of the light (more in creases) and would cost a ray a pixel.
    static constexpr float kCompensationShare = 1.0f;
    /// The bound's distance with Kollig-Keller compensation, as a multiple of clamp_distance.
    /// The compensation restores whatever the bound removes, so this trades VPL noise (a VPL
    /// close to a dark crease, within the paper's bound, is a spike there) against the
    /// continuation's noise; 2 lowered relMSE on every scene measured (docs/ACCURACY.md,
    /// "After the run"). IGI's first frame has it too: nothing restores the cut there yet (the
    /// frames after it do, in the running mean), but with Russian roulette its relMSE was 0.55
    /// to 0.90 times the paper's first frame's on ten of eleven scenes (docs/PERFORMANCE.md,
    /// "The first frame after a change").
    static constexpr float kCompensatedClampScale = 2.0f;
    /// The sharpness budget of the first frame after a change (glossy_bound holds for the frames
    /// after it): connections no sharper than Lambertian to Lambertian, the rest of a glossy
    /// lobe's VPL light left to its continuation ray. A VPL near a glossy surface is a spike
    /// that the 3 x 3 filter spreads but does not remove, and nothing accumulates over it; with
    /// 1 instead of 4 the first frame's relMSE fell on interior-glossy and cornell-glossy with
    /// each of seeds 1-3 (by 5-9 %), its speckle to about the diffuse room's, and scenes without
    /// glossy surfaces are unchanged. Since IGI's first frame shades no second point where its
    /// continuation rays land (LightingSet::compensationRays), the rest is not restored there,
    /// and the cut stays: leaving the lobes whole there (an infinite budget) made cornell-glossy's
    /// first frame far noisier than the cut's bias makes it wrong (measured by hand).
    static constexpr float kFirstFrameSharpnessBudget = 1.0f;

    /// How light paths end: Keller's quasi-random walk (the paper's, a fixed share of the
    /// lowest path indices going on at each diffuse bounce, then Russian roulette if `roulette`),
    /// or Russian roulette from the first bounce (photon tracing as in Jensen's photon maps).
    enum class PathEnd { KellerWalk, Roulette };
    /// Traces the light paths of `sampler`, calling `deposit` with the VPL each non-delta vertex
    /// makes (carrying its share of the light's power: the paths' flux / their count). The walk
    /// ends at the paper's length, or with `roulette` at the safety cap. `visit`, if given, sees
    /// every surface a path hits (mirrors and glass included), before that vertex's deposit.
    using Visit = std::function<void(std::uint32_t path, const SurfacePoint& hit)>;
    void traceLightPaths(const LightPathNumbers& sampler, PathEnd end, bool roulette,
                         RayCounters& rays, const std::function<void(const Vpl&)>& deposit,
                         const Visit& visit = {}) const;
    /// A VPL with a name that survives a scene change: the set, the light path and the vertex
    /// (surfaces met, mirrors and glass included) it was deposited at. A path that meets the
    /// same surfaces after a change deposits VPLs of the same names.
    struct NamedVpl {
        std::uint64_t id = 0;
        Vpl vpl;
    };
    static std::uint64_t vplId(std::uint32_t setIndex, std::uint32_t path, std::uint32_t vertex) {
        return (std::uint64_t(setIndex) << 40) | (std::uint64_t(path) << 12) | vertex;
    }
    /// The VPLs of set k's light paths as walkLightPaths traces them, but with the numbers of
    /// `stream` in `frame` and Russian roulette as asked, each named.
    std::vector<NamedVpl> namedVpls(SampleStream stream, std::uint32_t frame, bool roulette,
                                    std::uint32_t setIndex, RayCounters& rays) const;

    /// The set of k as build() makes it, but without VPLs from light paths: the light samples
    /// and the caustic photons of the frame's first image, for methods whose indirect light
    /// comes from elsewhere.
    /// Without `caustics`, no caustic photons either (a method that has its own).
    LightingSet buildDirect(std::uint32_t frame, std::uint32_t setIndex,
                            bool caustics = true) const;
    /// buildDirect's set with `indirect` as its VPLs (the `paths` light paths behind them): the
    /// first frame of a method that keeps its indirect light across frames.
    LightingSet buildWith(std::uint32_t frame, std::uint32_t setIndex, std::vector<Vpl> indirect,
                          std::uint32_t paths) const;
    const RenderSettings& settings() const { return settings_; }

    /// The caustic photons of every set of `frame`, each carrying 1 / K of its power: what
    /// every pixel of an accumulated frame gathers from (settings.poolCaustics). Shot once per
    /// frame by the first set that needs them; `shot` and `rays` receive a set's share.
    std::shared_ptr<const std::vector<CausticPhoton>> pooledCaustics(std::uint32_t frame,
                                                                     std::uint32_t& shot,
                                                                     RayCounters& rays) const;

  private:
    struct Pool {
        std::vector<CausticPhoton> photons;
        std::uint32_t shot = 0;
        RayCounters rays;
    };
    LightingSet assemble(std::uint32_t frame, std::uint32_t accumulation, std::uint32_t setIndex,
                         bool lightPaths, bool caustics = true) const;
    void sampleDirect(std::uint32_t frame, std::uint32_t setIndex, LightingSet& set) const;
    void walkLightPaths(std::uint32_t frame, std::uint32_t setIndex, LightingSet& set) const;

    const TraceableScene& scene_;
    const Lights& lights_;
    RenderSettings settings_;
    CausticShooter caustics_;
    std::uint32_t vplPaths_ = 0;
    int vplPool_ = 0;  ///< VPLs a set's light paths leave for the points to choose from; 0: none
    std::vector<std::uint32_t> survivors_;
    float minDistance_ = 0;         ///< the connection bound's distance at accumulation 0
    mutable std::mutex poolMutex_;  ///< guards pools_
    mutable std::map<std::uint32_t, std::shared_ptr<const Pool>> pools_;  ///< by frame
};

}  // namespace igi
