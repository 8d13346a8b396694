#include "scene/RenderSettingsJson.h"

#include "scene/JsonReader.h"

namespace igi {

namespace {

// A pair of small integers such as "interleave": [n, m].
void readPair(const JsonNode& node, std::int64_t lo, std::int64_t hi, int& x, int& y) {
    const auto e = node.elements(2);
    x = static_cast<int>(e[0].integer(lo, hi));
    y = static_cast<int>(e[1].integer(lo, hi));
}

void readInt(const JsonNode& section, const char* key, std::int64_t lo, std::int64_t hi, int& out) {
    if (auto v = section.find(key)) out = static_cast<int>(v->integer(lo, hi));
}

void readFloat(const JsonNode& section, const char* key, NumberRange range, float& out) {
    if (auto v = section.find(key)) out = v->real(range);
}

void readIntegrator(const JsonNode& section, RenderSettings& s) {
    if (auto v = section.find("integrator")) {
        s.integrator =
            v->choice({"igi", "path"}) == "igi" ? IntegratorKind::Igi : IntegratorKind::Path;
    }
    if (auto v = section.find("gi")) {
        const std::string gi = v->choice({"igi", "spt", "stream", "cache", "photonmap"});
        s.gi = gi == "igi"         ? GiMode::Igi
               : gi == "spt"       ? GiMode::Spt
               : gi == "cache"     ? GiMode::Cache
               : gi == "photonmap" ? GiMode::PhotonMap
                                   : GiMode::Stream;
    }
    readInt(section, "stream_vsls", 1, kMaxStreamVsls, s.streamVsls);
    readInt(section, "stream_photons", 1, 1 << 24, s.streamPhotons);
    readInt(section, "stream_window", 1, kMaxStreamWindow, s.streamWindow);
    readInt(section, "spt_groups", 1, kMaxSptGroups, s.sptGroups);
    readInt(section, "spt_paths", 1, 1024, s.sptPaths);
    // Pilots are the first paths of their group: at most all of them.
    readInt(section, "spt_pilots", 1, s.sptPaths, s.sptPilots);
    readInt(section, "spt_budget", 1, kMaxSptGroups, s.sptBudget);
    // Instant caching: site spacing (a fraction of the diagonal) and interpolation radius (in
    // spacings; below 1 many points find no site and are lit directly).
    readFloat(section, "cache_spacing", NumberRange::closed(1e-6, 0.999), s.cacheSpacing);
    readFloat(section, "cache_radius", NumberRange::closed(0.5, 16), s.cacheRadius);
    // Simulated photon mapping: photons (groups x photons per group), the radiance estimate's
    // neighbours, the final gather's rays and where the caustics are filtered.
    readInt(section, "photonmap_groups", 1, kMaxPhotonmapGroups, s.photonmapGroups);
    readInt(section, "photonmap_photons", 1, maxPhotonmapPhotonsPerGroup(s.photonmapGroups),
            s.photonmapPhotons);
    readInt(section, "photonmap_neighbours", 1, 4096, s.photonmapNeighbours);
    readInt(section, "photonmap_gather", 1, 65536, s.photonmapGather);
    if (auto v = section.find("photonmap_caustics"))
        s.photonmapScreenCaustics = v->choice({"screen", "grid"}) == "screen";
}

// Interleaving, direct light, VPLs and their clamp.
void readIgiLighting(const JsonNode& section, RenderSettings& s) {
    // "interleave": [n, m] sets of VPLs and photons, 1..16 each.
    if (auto v = section.find("interleave")) readPair(*v, 1, 16, s.interleaveX, s.interleaveY);
    // Shadow rays towards points sampled on the lights, per pixel.
    readInt(section, "direct_samples", 0, 256, s.directSamples);
    // How a point chooses those lights.
    if (auto v = section.find("light_sampling")) {
        const std::string how = v->choice({"auto", "power", "tree"});
        s.lightSampling = how == "auto"    ? LightSampling::Auto
                          : how == "power" ? LightSampling::Power
                                           : LightSampling::Tree;
    }
    // Light paths per set; 0 derives them from indirect_vpls.
    readInt(section, "vpl_paths", 0, 100000, s.vplPaths);
    readInt(section, "indirect_vpls", 0, 100000, s.indirectVpls);
    // How a point chooses among its set's VPLs, and the pool it chooses from.
    if (auto v = section.find("vpl_sampling")) {
        const std::string how = v->choice({"auto", "all", "importance"});
        s.vplSampling = how == "auto"  ? VplSampling::Auto
                        : how == "all" ? VplSampling::All
                                       : VplSampling::Importance;
    }
    readInt(section, "vpl_pool", 0, 100000, s.vplPool);
    // The first frame after a change takes the light samples and VPLs divided by this (0: auto).
    readInt(section, "first_frame_divisor", 0, kMaxFirstFrameDivisor, s.firstFrameDivisor);
    // Vertices of a light path, the one on the light included.
    readInt(section, "max_light_path_length", 1, 64, s.maxLightPathLength);
    // Fraction of the scene's bounding-box diagonal.
    readFloat(section, "clamp_distance", NumberRange::closedOpen(0, 1), s.clampDistance);
}

void readCausticsAndEyePaths(const JsonNode& section, RenderSettings& s) {
    readInt(section, "caustic_photons", 0, 10000000, s.causticPhotons);
    // Gather radius, a fraction of the scene's bounding-box diagonal.
    readFloat(section, "caustic_radius", NumberRange::open(0, 1), s.causticRadius);
    // Specular bounces followed from the eye.
    readInt(section, "max_eye_depth", 0, 64, s.maxEyeDepth);
    readInt(section, "light_edge_rays", 0, 1024, s.lightEdgeRays);
}

void readFilterAndOutput(const JsonNode& section, RenderSettings& s) {
    // Discontinuity buffer size; 0 means the interleaving size.
    if (auto v = section.find("filter")) readPair(*v, 0, 31, s.filterX, s.filterY);
    // Relative depth difference beyond which neighbours are not averaged.
    readFloat(section, "filter_depth_threshold", NumberRange::above(0), s.filterDepthThreshold);
    // Cosine between normals below which neighbours are not averaged.
    readFloat(section, "filter_normal_threshold", NumberRange::closed(-1, 1),
              s.filterNormalThreshold);
    if (auto v = section.find("accumulate")) s.accumulate = v->boolean();
}

// The converging estimator: "converge" sets every mean at once (true: all on, as the defaults;
// false: the paper's estimator), then the individual keys override it.
void readConvergence(const JsonNode& section, RenderSettings& s) {
    if (auto v = section.find("converge")) {
        const RenderSettings defaults;
        const bool on = v->boolean();
        s.roulette = on;
        s.clampCompensation = on ? defaults.clampCompensation : ClampCompensation::Off;
        s.indirectCausticPhotons = on ? defaults.indirectCausticPhotons : 0;
        s.progressiveRadius = on;
        s.progressiveFilter = on;
        s.poolCaustics = on;
    }
    if (auto v = section.find("roulette")) s.roulette = v->boolean();
    readInt(section, "roulette_max_length", 2, 1024, s.rouletteMaxLength);
    if (auto v = section.find("clamp_compensation")) {
        const std::string c = v->choice({"off", "shrink", "kollig-keller"});
        s.clampCompensation = c == "off"      ? ClampCompensation::Off
                              : c == "shrink" ? ClampCompensation::Shrink
                                              : ClampCompensation::KolligKeller;
    }
    readInt(section, "indirect_caustic_photons", 0, 10000000, s.indirectCausticPhotons);
    readFloat(section, "indirect_caustic_radius", NumberRange::open(0, 1), s.indirectCausticRadius);
    // The VPL bound's sharpness budget: 1 and more (1 leaves no glossy lobe to the VPLs).
    readFloat(section, "glossy_bound", NumberRange::closed(1, 1e6), s.glossyBound);
    if (auto v = section.find("progressive_radius")) s.progressiveRadius = v->boolean();
    if (auto v = section.find("progressive_filter")) s.progressiveFilter = v->boolean();
    if (auto v = section.find("pool_caustics")) s.poolCaustics = v->boolean();
    // How fast the caustic radius (and a shrinking clamp) shrinks; Knaus and Zwicker use 2/3.
    readFloat(section, "progressive_alpha", NumberRange::open(0, 1), s.progressiveAlpha);
}

void readPathTracerAndScheduling(const JsonNode& section, RenderSettings& s) {
    readInt(section, "path_samples", 1, 65536, s.pathSamples);
    readInt(section, "max_path_length", 1, 1024, s.maxPathLength);
    readInt(section, "tile_size", 1, 1024, s.tileSize);
    if (auto v = section.find("seed")) s.seed = v->unsignedInteger();
}

}  // namespace

void applyRenderSettingsJson(const nlohmann::json& json, RenderSettings& settings,
                             const std::string& file, const std::string& jsonPathPrefix) {
    const JsonNode section(json, file, jsonPathPrefix);
    section.checkKeys({"integrator",
                       "gi",
                       "stream_vsls",
                       "stream_photons",
                       "stream_window",
                       "spt_groups",
                       "spt_paths",
                       "spt_pilots",
                       "spt_budget",
                       "cache_spacing",
                       "cache_radius",
                       "photonmap_groups",
                       "photonmap_photons",
                       "photonmap_neighbours",
                       "photonmap_gather",
                       "photonmap_caustics",
                       "interleave",
                       "direct_samples",
                       "light_sampling",
                       "vpl_paths",
                       "indirect_vpls",
                       "vpl_sampling",
                       "vpl_pool",
                       "first_frame_divisor",
                       "max_light_path_length",
                       "clamp_distance",
                       "caustic_photons",
                       "caustic_radius",
                       "max_eye_depth",
                       "light_edge_rays",
                       "filter",
                       "filter_depth_threshold",
                       "filter_normal_threshold",
                       "accumulate",
                       "path_samples",
                       "max_path_length",
                       "tile_size",
                       "seed",
                       "converge",
                       "roulette",
                       "roulette_max_length",
                       "clamp_compensation",
                       "indirect_caustic_photons",
                       "indirect_caustic_radius",
                       "glossy_bound",
                       "progressive_radius",
                       "progressive_filter",
                       "pool_caustics",
                       "progressive_alpha"});
    // Read into a copy so that a failure leaves `settings` untouched.
    RenderSettings s = settings;
    readIntegrator(section, s);
    readIgiLighting(section, s);
    readCausticsAndEyePaths(section, s);
    readFilterAndOutput(section, s);
    readConvergence(section, s);
    readPathTracerAndScheduling(section, s);
    settings = s;
}

namespace {

const char* lightSamplingName(LightSampling s) {
    return s == LightSampling::Auto ? "auto" : s == LightSampling::Power ? "power" : "tree";
}

const char* vplSamplingName(VplSampling s) {
    return s == VplSampling::Auto ? "auto" : s == VplSampling::All ? "all" : "importance";
}

const char* compensationName(ClampCompensation c) {
    return c == ClampCompensation::Off      ? "off"
           : c == ClampCompensation::Shrink ? "shrink"
                                            : "kollig-keller";
}

}  // namespace

nlohmann::json renderSettingsJson(const RenderSettings& s) {
    // Every key applyRenderSettingsJson reads but "converge", which only sets the others.
    return {{"integrator", s.integrator == IntegratorKind::Path ? "path" : "igi"},
            {"gi", giModeName(s.gi)},
            {"stream_vsls", s.streamVsls},
            {"stream_photons", s.streamPhotons},
            {"stream_window", s.streamWindow},
            {"spt_groups", s.sptGroups},
            {"spt_paths", s.sptPaths},
            {"spt_pilots", s.sptPilots},
            {"spt_budget", s.sptBudget},
            {"cache_spacing", s.cacheSpacing},
            {"cache_radius", s.cacheRadius},
            {"photonmap_groups", s.photonmapGroups},
            {"photonmap_photons", s.photonmapPhotons},
            {"photonmap_neighbours", s.photonmapNeighbours},
            {"photonmap_gather", s.photonmapGather},
            {"photonmap_caustics", s.photonmapScreenCaustics ? "screen" : "grid"},
            {"interleave", {s.interleaveX, s.interleaveY}},
            {"direct_samples", s.directSamples},
            {"light_sampling", lightSamplingName(s.lightSampling)},
            {"vpl_paths", s.vplPaths},
            {"indirect_vpls", s.indirectVpls},
            {"vpl_sampling", vplSamplingName(s.vplSampling)},
            {"vpl_pool", s.vplPool},
            {"first_frame_divisor", s.firstFrameDivisor},
            {"max_light_path_length", s.maxLightPathLength},
            {"clamp_distance", s.clampDistance},
            {"caustic_photons", s.causticPhotons},
            {"caustic_radius", s.causticRadius},
            {"max_eye_depth", s.maxEyeDepth},
            {"light_edge_rays", s.lightEdgeRays},
            {"filter", {s.filterX, s.filterY}},
            {"filter_depth_threshold", s.filterDepthThreshold},
            {"filter_normal_threshold", s.filterNormalThreshold},
            {"accumulate", s.accumulate},
            {"path_samples", s.pathSamples},
            {"max_path_length", s.maxPathLength},
            {"tile_size", s.tileSize},
            {"seed", s.seed},
            {"roulette", s.roulette},
            {"roulette_max_length", s.rouletteMaxLength},
            {"clamp_compensation", compensationName(s.clampCompensation)},
            {"indirect_caustic_photons", s.indirectCausticPhotons},
            {"indirect_caustic_radius", s.indirectCausticRadius},
            {"glossy_bound", s.glossyBound},
            {"progressive_radius", s.progressiveRadius},
            {"progressive_filter", s.progressiveFilter},
            {"pool_caustics", s.poolCaustics},
            {"progressive_alpha", s.progressiveAlpha}};
}

}  // namespace igi
