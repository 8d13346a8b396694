#pragma once

#include <cstdint>
#include <string>

namespace igi {

enum class IntegratorKind : std::uint8_t {
    Igi,   ///< Instant Global Illumination (the paper's algorithm)
    Path,  ///< brute-force path tracing, the reference
};

/// Every parameter of rendering, as plain data. Read from a scene file's "render" section and
/// overridden by the master's command line; documented in docs/SCENE_FORMAT.md. Defaults are
/// the paper's Cornell-box setting: 3 x 3 interleaving and filter, 4 direct and 18 indirect
/// shadow rays per pixel, 500 caustic photons, light paths of length 4.
struct RenderSettings {
    IntegratorKind integrator = IntegratorKind::Igi;

    // Interleaved sampling: n x m sets P_k and C_k, k = 1 .. n*m.
    int interleaveX = 3;
    int interleaveY = 3;

    // Direct light: points sampled on the lights (by power) per set; one shadow ray each.
    int directSamples = 4;

    // Indirect light from virtual point lights (VPLs).
    int vplPaths = 0;            ///< light paths per set; 0 derives it from indirectVpls
    int indirectVpls = 18;       ///< wanted indirect VPLs per set when vplPaths is 0
    int maxLightPathLength = 4;  ///< vertices of a light path, the one on the light included
    /// Minimum distance in the VPL geometry term, as a fraction of the scene's bounding-box
    /// diagonal, so that the clamp means the same at every scale.
    float clampDistance = 0.02f;

    // Caustics: photons shot at mirrors and glass per set, gathered within a fixed radius.
    int causticPhotons = 500;
    float causticRadius = 0.01f;  ///< fraction of the scene's bounding-box diagonal

    // Eye paths: specular bounces followed to a diffuse end point.
    int maxEyeDepth = 8;

    // Discontinuity buffer on the master; a size of 0 means "the interleaving size".
    int filterX = 0;
    int filterY = 0;
    float filterDepthThreshold =
        0.05f;  ///< neighbours whose depth differs by more (relative) are kept apart
    float filterNormalThreshold =
        0.9f;  ///< neighbours whose normals' cosine is lower are kept apart

    bool accumulate = true;  ///< average successive frames while nothing changes

    // Reference path tracer.
    int pathSamples = 16;    ///< samples per pixel per frame
    int maxPathLength = 16;  ///< path vertices, Russian roulette after the third

    int tileSize = 32;       ///< a tile covers tileSize x tileSize pixels of one k
    std::uint64_t seed = 1;  ///< session seed for every random bit vector

    int effectiveFilterX() const { return filterX > 0 ? filterX : interleaveX; }
    int effectiveFilterY() const { return filterY > 0 ? filterY : interleaveY; }
    int setCount() const { return interleaveX * interleaveY; }
    bool operator==(const RenderSettings&) const = default;
};

}  // namespace igi
