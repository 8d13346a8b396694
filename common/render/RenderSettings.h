#pragma once

#include <algorithm>

#include <cstddef>
#include <cstdint>
#include <string>

namespace igi {

enum class IntegratorKind : std::uint8_t {
    Igi,   ///< Instant Global Illumination (the paper's algorithm)
    Path,  ///< brute-force path tracing, the reference
};

/// The most epochs a photon stream's pool may span: a client keeps that many epochs' photons.
constexpr int kMaxStreamWindow = 64;
/// The most surface lights of photon streaming: their placement and each photon's deposit
/// search every one of them.
constexpr int kMaxStreamVsls = 16384;

/// How a client builds and keeps the lighting of a frame: the family of GI methods that share
/// the cluster (client/lighting/LightingMethod.h). Accumulated frames of a still view converge the
/// same way in every mode; the modes differ in what the first frame after a change shows.
enum class GiMode : std::uint8_t {
    Igi,        ///< fresh light paths every frame (the paper's instant global illumination)
    Stream,     ///< photon streaming (Meneveaux and Bridault 2008): a pool of recent photons
                ///< deposited on virtual surface-element lights that move with their objects
    Spt,        ///< selective photon tracing (Dmitriev et al. 2002): a pool of light paths in
                ///< groups, only the groups a change touches traced again
    Cache,      ///< instant caching (Debattista et al. 2009): the VPLs' light on Lambertian
                ///< surfaces cached at object-space sites and interpolated, kept across frames
    PhotonMap,  ///< Larsen and Christensen (2004): selective photon emission, a photon map's
                ///< light final-gathered at the sites, caustics filtered in screen space
};

/// The name of a mode in scene files, on the command line and in the status.
inline const char* giModeName(GiMode mode) {
    switch (mode) {
        case GiMode::Stream:
            return "stream";
        case GiMode::Spt:
            return "spt";
        case GiMode::Cache:
            return "cache";
        case GiMode::PhotonMap:
            return "photonmap";
        case GiMode::Igi:
            break;
    }
    return "igi";
}

/// The most photon groups of simulated photon mapping: every frame checks a photon of each.
constexpr int kMaxPhotonmapGroups = 65536;
/// The most photons of simulated photon mapping (groups x photons per group): each keeps its
/// path and its hits on every client.
constexpr int kMaxPhotonmapPhotons = 1 << 20;
/// The photons per group that `groups` groups may have.
inline int maxPhotonmapPhotonsPerGroup(int groups) {
    return std::min(4096, kMaxPhotonmapPhotons / std::max(1, groups));
}

/// The most path groups of selective photon tracing: every scene change checks each one.
constexpr int kMaxSptGroups = 65536;

/// How a point that receives direct light chooses among the scene's lights.
enum class LightSampling : std::uint8_t {
    Auto,   ///< Tree from kLightTreeMinLights lights on, Power below
    Power,  ///< by emitted power alone, the same for every point (the paper's choice)
    Tree,   ///< by a light tree's estimate of each light's contribution at the point
};

/// From this many emitters (emissive triangles and point lights) on, Auto uses the tree. Below
/// it the lights are few enough that power alone spends the samples well, and the images stay
/// exactly as they were (a quad light is two triangles: up to three quad lights keep power).
constexpr std::size_t kLightTreeMinLights = 8;

inline bool usesLightTree(LightSampling sampling, std::size_t lights) {
    return sampling == LightSampling::Tree ||
           (sampling == LightSampling::Auto && lights >= kLightTreeMinLights);
}

/// How a point chooses the indirect VPLs it connects to (client/lights/VplChoice.h).
enum class VplSampling : std::uint8_t {
    Auto,        ///< Importance from kLightTreeMinLights emitters on, All below
    All,         ///< every VPL of its set (the paper's)
    Importance,  ///< vplPool VPLs per set, indirectVpls of them per point, by importance
};

inline bool usesVplChoice(VplSampling sampling, std::size_t lights) {
    return sampling == VplSampling::Importance ||
           (sampling == VplSampling::Auto && lights >= kLightTreeMinLights);
}

/// The pool a set keeps when VPLs are chosen by importance and vplPool is 0: this many times the
/// VPLs each point connects to.
constexpr int kVplPoolFactor = 8;

/// What restores the energy that bounding the VPL connections removes.
enum class ClampCompensation : std::uint8_t {
    Off,           ///< nothing: the bound's energy is lost (the paper's estimator)
    Shrink,        ///< the bound loosens as frames accumulate (progressive clamp distance)
    KolligKeller,  ///< a short path-traced continuation carries the bounded part (2004)
};

/// Every parameter of rendering, as plain data. Read from a scene file's "render" section and
/// overridden by the master's command line; documented in docs/SCENE_FORMAT.md. Defaults are
/// the paper's Cornell-box setting: 3 x 3 interleaving and filter, 4 direct and 18 indirect
/// shadow rays per pixel, 500 caustic photons, light paths of length 4.
struct RenderSettings {
    IntegratorKind integrator = IntegratorKind::Igi;
    GiMode gi = GiMode::Igi;

    // Interleaved sampling: n x m sets P_k and C_k, k = 1 .. n*m.
    int interleaveX = 3;
    int interleaveY = 3;

    // Direct light: points sampled on the lights per set (by power), or, with a light tree, the
    // numbers per set that each point turns into its own light samples; one shadow ray each.
    int directSamples = 4;
    LightSampling lightSampling = LightSampling::Auto;

    // Indirect light from virtual point lights (VPLs).
    int vplPaths = 0;  ///< light paths per set; 0 derives it from indirectVpls
    int indirectVpls =
        18;  ///< wanted indirect VPLs per set (per point with a pool) when vplPaths is 0
    VplSampling vplSampling = VplSampling::Auto;
    /// With VPLs chosen by importance: the VPLs each set's light paths leave (when vplPaths is
    /// 0), of which each point connects to indirectVpls; 0: kVplPoolFactor x indirectVpls.
    int vplPool = 0;
    int effectiveVplPool() const { return vplPool > 0 ? vplPool : kVplPoolFactor * indirectVpls; }
    /// The first frame after a change (and every frame of a session without accumulation) is
    /// what a user sees while moving: IGI renders it with the light samples and the indirect
    /// VPLs above divided by this (rounded up: a count of 1 stays 1). Where the points choose
    /// their VPLs by importance, the pool they choose from and the light paths stay the
    /// accumulated frames': choosing 6 of 144 VPLs gave 1.13 times 4 + 18's first-frame relMSE
    /// in the diffuse room, 6 of 48 gave 1.41 times for about a quarter less time
    /// (kAutoFirstFrameDivisor). Elsewhere each point connects to every VPL of its set, and the
    /// set has fewer (unless vplPaths fixes the light paths: then only the light samples are
    /// divided). 1 keeps the first frame as the others; 0 (auto) is kAutoFirstFrameDivisor where
    /// VPLs are chosen by importance (many emitters), 1 elsewhere (the few-light boxes). The
    /// frames accumulated after it keep the full numbers, so the running mean converges as
    /// before.
    int firstFrameDivisor = 0;
    /// Vertices of a light path, the one on the light included, in Keller's quasi-random walk
    /// (stratified over the paths); with `roulette`, the paths alive at its end go on.
    int maxLightPathLength = 4;
    /// Minimum distance in the VPL geometry term, as a fraction of the scene's bounding-box
    /// diagonal, so that the clamp means the same at every scale.
    float clampDistance = 0.02f;

    // Caustics: photons shot at mirrors and glass per set, gathered within a fixed radius.
    int causticPhotons = 500;
    float causticRadius = 0.01f;  ///< fraction of the scene's bounding-box diagonal

    // Eye paths: specular bounces followed to a diffuse end point.
    int maxEyeDepth = 8;
    /// Eye rays of their own, per pixel and frame, that gather the light seen directly
    /// (emitters, the sky) where the outline of an emissive triangle crosses the pixel
    /// (LightEdges): one eye ray finds there a light much brighter than the rest of the
    /// footprint in few frames. 0: the eye ray's own hit alone, everywhere.
    int lightEdgeRays = 16;

    // Discontinuity buffer on the master; a size of 0 means "the interleaving size".
    int filterX = 0;
    int filterY = 0;
    float filterDepthThreshold =
        0.05f;  ///< neighbours whose depth differs by more (relative) are kept apart
    float filterNormalThreshold =
        0.9f;  ///< neighbours whose normals' cosine is lower are kept apart

    bool accumulate = true;  ///< average successive frames while nothing changes

    // Convergence while the view holds still ("converge" in a scene file turns all of these on
    // or off at once). Each removes one bias of instant radiosity, so that accumulated frames
    // converge to the rendering equation's answer instead of a darker one.
    bool roulette = true;        ///< light paths go on by Russian roulette past the walk
    int rouletteMaxLength = 64;  ///< safety cap on a light path's vertices under roulette
    ClampCompensation clampCompensation = ClampCompensation::KolligKeller;
    /// The sharpness budget S of the VPL bound (client/shading/ConnectionBound.h): a connection
    /// whose two ends' sharpness multiply to more is cut down to S / (s_x s_y), and the
    /// compensation adds the rest by BRDF sampling. Only with a compensation.
    float glossyBound = 4.0f;
    /// Photons shot per set from the VPLs at mirrors and glass (diffuse-specular-diffuse
    /// light, which no VPL can carry); 0 leaves that light out.
    int indirectCausticPhotons = 1000;
    /// Their gather radius, a fraction of the scene's diagonal: wider than the caustics', as
    /// the light they carry is smooth (and they are few per set).
    float indirectCausticRadius = 0.05f;
    /// In accumulated frames every pixel gathers the caustic photons of every set (each with
    /// 1 / K of its power), not its own set's alone: where the progressive filter withdraws
    /// the discontinuity buffer (a caustic's edges), a pixel still sees all the frame's photons.
    bool poolCaustics = true;
    /// Progressive photon mapping (Knaus and Zwicker 2011): the caustic radius of accumulated
    /// frame i is r_i^2 = r_0^2 prod_{k=1..i} (k + alpha) / (k + 1) (render/ProgressiveSchedule.h).
    bool progressiveRadius = true;
    /// The discontinuity buffer's blur is withdrawn, pixel by pixel, where the accumulated
    /// frames show it biased (Accumulator), so that the accumulated image converges to the
    /// unblurred one.
    bool progressiveFilter = true;
    /// alpha of that schedule, in (0, 1); the shrinking clamp distance
    /// (ClampCompensation::Shrink) follows the same schedule.
    float progressiveAlpha = 2.0f / 3.0f;

    // Photon streaming (GiMode::Stream).
    int streamVsls = 256;      ///< virtual surface-element lights placed on the geometry
    int streamPhotons = 4096;  ///< light paths shot per scene epoch into the pool
    int streamWindow = 8;      ///< epochs whose photons the pool holds (its size / streamPhotons)

    // Selective photon tracing (GiMode::Spt). The pool is sptGroups x sptPaths light paths.
    int sptGroups = 36;  ///< path groups G (2^a 3^b ...: the Halton periodicity groups them)
    int sptPaths = 3;    ///< light paths per group
    int sptPilots = 1;   ///< of which pilots, traced on every change to detect it (<= sptPaths)
    int sptBudget = 6;   ///< groups traced again per frame at most

    // Instant caching (GiMode::Cache).
    float cacheSpacing = 0.02f;  ///< distance between cache sites, a fraction of the diagonal
    float cacheRadius = 2.0f;    ///< interpolation radius, in site spacings

    // Simulated photon mapping (GiMode::PhotonMap); its sites are instant caching's.
    int photonmapGroups = 256;            ///< photon groups G of the selective emission
    int photonmapPhotons = 16;            ///< photons per group P: one of each is checked per frame
    int photonmapNeighbours = 64;         ///< photon hits in a radiance estimate
    int photonmapGather = 64;             ///< final gather rays per site
    bool photonmapScreenCaustics = true;  ///< caustics by the screen-space filter (else the grid)

    // Reference path tracer.
    int pathSamples = 16;    ///< samples per pixel per frame
    int maxPathLength = 16;  ///< path vertices, Russian roulette after the third

    int tileSize = 32;       ///< a tile covers tileSize x tileSize pixels of one k
    std::uint64_t seed = 1;  ///< session seed for every random bit vector

    /// firstFrameDivisor, with auto resolved for a scene of `lights` emitters.
    int effectiveFirstFrameDivisor(std::size_t lights) const;
    /// The settings IGI renders a first frame with (firstFrameDivisor applied); *this where the
    /// divisor is 1 or the frame is not IGI's own (the path tracer, the other GI modes, whose
    /// first frames keep what their method keeps).
    RenderSettings firstFrameSettings(std::size_t lights) const;

    int effectiveFilterX() const { return filterX > 0 ? filterX : interleaveX; }
    int effectiveFilterY() const { return filterY > 0 ? filterY : interleaveY; }
    int setCount() const { return interleaveX * interleaveY; }
    bool operator==(const RenderSettings&) const = default;
};

/// Where the points choose their VPLs by importance, the first frame after a change takes a
/// quarter of the light samples and VPLs (4 + 18 become 1 + 5 per point, from the full pool).
/// Chosen on the diffuse room and the Sponza arcades with scripts/first_frame_pairs.py (first
/// frames at 160 x 120, medians of 8 seeds, against the path-traced references; the client's
/// render seconds for 3 frames at 320 x 240, two rounds; its run of 2026-11-29 16:10 UTC):
/// 1 + 5 took 0.48-0.57 and 0.57-0.63 of 4 + 18's time for 1.29 and 1.25 times its relMSE;
/// 2 + 6 took 0.62-0.64 and 0.62-0.70 for 1.13 and 1.15; 2 + 6 from a pool of 48 (the pool
/// divided too) 0.46-0.50 and 0.58-0.65 for 1.41 and 1.78. The rooms' first frames had a tenth of
/// the error of the day issue 36 was filed, which a quarter of the rays turns into time; the
/// arcades' had as much, and pay for the speed in error (docs/PERFORMANCE.md, "The first frame
/// after a change").
constexpr int kAutoFirstFrameDivisor = 4;
/// The largest divisor a scene file or command takes.
constexpr int kMaxFirstFrameDivisor = 64;

inline int RenderSettings::effectiveFirstFrameDivisor(std::size_t lights) const {
    if (firstFrameDivisor > 0) return firstFrameDivisor;
    return usesVplChoice(vplSampling, lights) ? kAutoFirstFrameDivisor : 1;
}

inline RenderSettings RenderSettings::firstFrameSettings(std::size_t lights) const {
    const int k = effectiveFirstFrameDivisor(lights);
    if (k <= 1 || integrator != IntegratorKind::Igi || gi != GiMode::Igi) return *this;
    // Rounded up, so that a count of 1 stays 1 and 0 (none, or derived) stays 0.
    const auto divide = [k](int n) { return n > 0 ? (n + k - 1) / k : n; };
    RenderSettings s = *this;
    s.directSamples = divide(directSamples);
    s.indirectVpls = divide(indirectVpls);
    // The pool, and the light paths derived from it, as the accumulated frames' (used only
    // where VPLs are chosen by importance: without a pool the paths follow indirectVpls).
    if (indirectVpls > 0) s.vplPool = effectiveVplPool();
    s.firstFrameDivisor = 1;
    return s;
}

}  // namespace igi
