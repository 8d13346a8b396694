#pragma once
// Scenes built in code and a small in-process renderer, for the client's tests.

#include <cmath>
#include <limits>
#include <map>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "TileRenderer.h"
#include "image/Image.h"
#include "math/Color.h"
#include "render/Accumulator.h"
#include "render/DiscontinuityFilter.h"
#include "render/FrameBuffer.h"
#include "render/Tile.h"
#include "scene/Scene.h"
#include "scene/SceneState.h"
#include "tracing/EmbreeDevice.h"
#include "tracing/SceneGeometry.h"
#include "tracing/TraceableScene.h"
#include "util/ThreadPool.h"

namespace igi::testing {

/// An icosphere of `radius` about `centre` with radial vertex normals, wound outward.
inline Mesh makeIcosphere(int subdivisions, float radius, glm::vec3 centre,
                          std::uint32_t material) {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    std::vector<glm::vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (auto& p : v) p = glm::normalize(p);
    std::vector<glm::uvec3> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int s = 0; s < subdivisions; ++s) {
        std::map<std::pair<unsigned, unsigned>, unsigned> cache;
        auto mid = [&](unsigned a, unsigned b) {
            auto key = std::minmax(a, b);
            auto it = cache.find(key);
            if (it != cache.end()) return it->second;
            v.push_back(glm::normalize(v[a] + v[b]));
            return cache[key] = unsigned(v.size() - 1);
        };
        std::vector<glm::uvec3> next;
        for (auto tri : f) {
            const unsigned ab = mid(tri.x, tri.y), bc = mid(tri.y, tri.z), ca = mid(tri.z, tri.x);
            next.insert(next.end(),
                        {{tri.x, ab, ca}, {tri.y, bc, ab}, {tri.z, ca, bc}, {ab, bc, ca}});
        }
        f = std::move(next);
    }
    Mesh mesh;
    mesh.name = "sphere";
    mesh.normals = v;
    for (auto& p : v) mesh.positions.push_back(centre + radius * p);
    mesh.triangles = f;
    mesh.materialIds.assign(f.size(), material);
    return mesh;
}

/// A parallelogram corner + s * e1 + t * e2, facing cross(e1, e2).
inline Mesh makeQuad(glm::vec3 corner, glm::vec3 e1, glm::vec3 e2, std::uint32_t material) {
    Mesh mesh;
    mesh.name = "quad";
    mesh.positions = {corner, corner + e1, corner + e1 + e2, corner + e2};
    mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
    mesh.materialIds = {material, material};
    return mesh;
}

/// A directional light named "sun" shining along `direction` (normalized here) with this grey
/// irradiance, a disk of `angleDeg` (0: a delta).
inline PunctualLight sun(glm::vec3 direction, float irradiance, float angleDeg = 0.0f) {
    PunctualLight l;
    l.name = "sun";
    l.kind = LightKind::Directional;
    l.direction = glm::normalize(direction);
    l.intensity = glm::vec3(irradiance);
    l.angleDeg = angleDeg;
    return l;
}

inline Material diffuse(glm::vec3 albedo) {
    Material m;
    m.name = "diffuse";
    m.diffuse = albedo;
    return m;
}

/// A cuboid of half extents `half` about `centre`, turned by `yawDeg` about the y axis, with
/// its faces wound outward.
inline Mesh makeBox(glm::vec3 centre, glm::vec3 half, float yawDeg, std::uint32_t material) {
    const float a = yawDeg * 3.14159265f / 180.0f, c = std::cos(a), s = std::sin(a);
    auto place = [&](glm::vec3 p) {
        p *= half;
        return centre + glm::vec3(c * p.x + s * p.z, p.y, -s * p.x + c * p.z);
    };
    Mesh mesh;
    mesh.name = "box";
    for (int i = 0; i < 8; ++i)
        mesh.positions.push_back(
            place({i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f, i & 4 ? 1.0f : -1.0f}));
    // Corner i has x = bit 0, y = bit 1, z = bit 2; each face counter-clockwise seen from outside.
    const unsigned faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                  {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (const auto& f : faces) {
        mesh.triangles.push_back({f[0], f[1], f[2]});
        mesh.triangles.push_back({f[0], f[2], f[3]});
    }
    mesh.materialIds.assign(mesh.triangles.size(), material);
    return mesh;
}

/// A small Cornell-like room of side `scale` (corner at the origin, open toward +z where the
/// camera is): white floor, ceiling and back wall, red left and green right walls, a turned
/// box, a quad light under the ceiling (radiance independent of scale) and a point light of
/// intensity 0.3 scale^2, so that the image is the same at every scale. With `glassBall`, a
/// glass sphere stands on the floor. Materials: 0 white, 1 red, 2 green, 3 glass.
inline Scene cornellBox(float scale, bool glassBall = false) {
    Scene scene;
    scene.materials = {diffuse(glm::vec3(0.75f)), diffuse({0.7f, 0.15f, 0.1f}),
                       diffuse({0.15f, 0.6f, 0.15f})};
    Material glass;
    glass.name = "glass";
    glass.glass = true;
    scene.materials.push_back(glass);
    const float s = scale;
    const glm::vec3 x(s, 0, 0), y(0, s, 0), z(0, 0, s), o(0.0f);
    scene.meshes = {
        makeQuad(o, z, x, 0),  // floor, facing +y
        makeQuad(y, x, z, 0),  // ceiling, facing -y
        makeQuad(o, x, y, 0),  // back wall, facing +z
        makeQuad(o, y, z, 1),  // left wall, facing +x
        makeQuad(x, z, y, 2),  // right wall, facing -x
        makeBox(s * glm::vec3(0.65f, 0.2f, 0.35f), s * glm::vec3(0.15f, 0.2f, 0.15f), 20.0f, 0)};
    if (glassBall)
        scene.meshes.push_back(makeIcosphere(2, 0.14f * s, s * glm::vec3(0.3f, 0.145f, 0.62f), 3));
    QuadLight light;
    light.name = "ceiling light";
    light.corner = s * glm::vec3(0.35f, 0.995f, 0.35f);
    light.edge1 = s * glm::vec3(0.3f, 0, 0);
    light.edge2 = s * glm::vec3(0, 0, 0.3f);  // cross(edge1, edge2) points down
    light.radiance = glm::vec3(8.0f);
    scene.quadLights.push_back(light);
    scene.punctualLights.push_back(
        pointLight("fill", s * glm::vec3(0.2f, 0.8f, 0.75f), glm::vec3(0.3f * s * s)));
    scene.camera = {s * glm::vec3(0.5f, 0.5f, 1.9f), s * glm::vec3(0.5f, 0.5f, 0.0f),
                    glm::vec3(0, 1, 0), 40};
    scene.image = {48, 36, 0};
    return scene;
}

/// Values of a tile's planes that are NaN or infinite (depth may be +inf: no surface, but not
/// NaN or -inf).
inline std::size_t countNonFinite(const TileChannels& c) {
    std::size_t bad = 0;
    for (const auto* plane : {&c.irradiance, &c.reflectance, &c.normal, &c.unfiltered, &c.glossy})
        for (const glm::vec3& v : *plane) bad += isFinite(v) ? 0 : 1;
    for (float d : c.depth) bad += std::isnan(d) || d == -std::numeric_limits<float>::infinity();
    return bad;
}

/// Renders `frames` frames of a whole image in this process (tiles, discontinuity buffer,
/// accumulation: the pipeline without the network) and returns the accumulated mean.
class InProcessRenderer {
  public:
    explicit InProcessRenderer(const Scene& scene, unsigned threads = 2)
        : scene_(scene),
          geometry_(device_, scene_),
          traceable_(geometry_),
          renderer_(traceable_, SceneState::of(scene_), scene_.render, scene_.image,
                    LightingContext{&scene_, 0, 0, nullptr}),
          pool_(threads) {}

    /// `firstAccumulation`: the first frame's place in the accumulation, as the master would
    /// send it (the first frame after a change is 0, and renders the paper's estimator).
    Image render(int frames, std::uint32_t firstFrame = 0, std::uint32_t firstAccumulation = 0) {
        const RenderSettings& s = scene_.render;
        const int w = scene_.image.width, h = scene_.image.height;
        const auto tiles = makeTiles(w, h, s.interleaveX, s.interleaveY, s.tileSize);
        Accumulator accumulator;
        accumulator.reset(w, h, s.progressiveFilter, s.effectiveFilterX(), s.effectiveFilterY());
        FrameBuffer frame;
        std::vector<glm::vec3> filtered(std::size_t(w) * h), unfiltered(filtered.size());
        for (int f = 0; f < frames; ++f) {
            frame.reset(w, h);
            for (const Tile& t : tiles) {
                // The frame's place in the accumulation, as the master would send it.
                const proto::TileResult r =
                    renderer_.renderNow(pool_, firstFrame + std::uint32_t(f), t,
                                        s.accumulate ? firstAccumulation + std::uint32_t(f) : 0);
                frame.scatter(t, s.interleaveX, s.interleaveY, r.channels);
                shadowRays_ += r.stats.shadowRays;
                nonFinite_ += countNonFinite(r.channels);
            }
            discontinuityFilterRows(frame,
                                    {s.effectiveFilterX(), s.effectiveFilterY(),
                                     s.filterDepthThreshold, s.filterNormalThreshold},
                                    0, h, filtered);
            compositeUnfilteredRows(frame, 0, h, unfiltered);
            accumulator.addRows(filtered, unfiltered, 0, h);
            accumulator.endFrame();
        }
        Image image(w, h);
        accumulator.meanRows(image.pixels, 0, h);
        return image;
    }

    TileRenderer& renderer() { return renderer_; }
    const TraceableScene& traceable() const { return traceable_; }
    ThreadPool& pool() { return pool_; }
    std::uint64_t shadowRays() const { return shadowRays_; }
    /// NaN or infinite values in every tile rendered so far (see countNonFinite).
    std::size_t nonFiniteValues() const { return nonFinite_; }

  private:
    Scene scene_;
    EmbreeDevice device_;
    SceneGeometry geometry_;
    TraceableScene traceable_;
    TileRenderer renderer_;
    ThreadPool pool_;
    std::uint64_t shadowRays_ = 0;
    std::size_t nonFinite_ = 0;
};

inline glm::dvec3 meanOf(const Image& image) {
    glm::dvec3 sum(0.0);
    for (const auto& p : image.pixels) sum += glm::dvec3(p);
    return sum / double(image.pixels.size());
}

/// IGI's accumulated image of a scene and our path tracer's image of the same scene: the path
/// tracer shares the BRDF and light code and is the exact reference that IGI must converge to.
struct IgiAndPathImages {
    Image igi, path;
    /// NaN or infinite values in the tiles of either renderer.
    std::size_t nonFinite = 0;

    glm::dvec3 igiMean() const { return meanOf(igi); }
    glm::dvec3 pathMean() const { return meanOf(path); }
    /// IGI's mean over the path tracer's, in the luminance-like green channel.
    double meanRatio() const { return igiMean().y / pathMean().y; }
};

/// Renders `igiFrames` accumulated IGI frames of `scene`, then `pathFrames` frames of
/// `pathSamples` paths per pixel with the path tracer; `maxPathLength` > 0 overrides the
/// scene's path length for the path tracer.
inline IgiAndPathImages renderIgiAndPath(Scene scene, int igiFrames, int pathSamples,
                                         int pathFrames = 1, int maxPathLength = 0) {
    IgiAndPathImages out;
    scene.render.integrator = IntegratorKind::Igi;
    InProcessRenderer igi(scene);
    out.igi = igi.render(igiFrames);
    scene.render.integrator = IntegratorKind::Path;
    scene.render.pathSamples = pathSamples;
    if (maxPathLength > 0) scene.render.maxPathLength = maxPathLength;
    InProcessRenderer path(scene);
    out.path = path.render(pathFrames);
    out.nonFinite = igi.nonFiniteValues() + path.nonFiniteValues();
    return out;
}

/// The mean length of the per-pixel difference of two images of one size (to tell that a
/// feature changed what is rendered).
inline double meanDifference(const Image& a, const Image& b) {
    double difference = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
        difference += glm::length(glm::dvec3(a.pixels[i] - b.pixels[i]));
    return difference / double(a.pixels.size());
}

}  // namespace igi::testing
