#pragma once
// Scenes built in code and a small in-process renderer, for the client's tests.

#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "EmbreeDevice.h"
#include "SceneGeometry.h"
#include "TileRenderer.h"
#include "TraceableScene.h"
#include "image/Image.h"
#include "render/Accumulator.h"
#include "render/DiscontinuityFilter.h"
#include "render/FrameBuffer.h"
#include "render/Tile.h"
#include "scene/Scene.h"
#include "scene/SceneState.h"
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

inline Material diffuse(glm::vec3 albedo) {
    Material m;
    m.name = "diffuse";
    m.diffuse = albedo;
    return m;
}

/// Renders `frames` frames of a whole image in this process (tiles, discontinuity buffer,
/// accumulation: the pipeline without the network) and returns the accumulated mean.
class InProcessRenderer {
  public:
    explicit InProcessRenderer(const Scene& scene, unsigned threads = 2)
        : scene_(scene),
          geometry_(device_, scene_),
          traceable_(geometry_),
          renderer_(traceable_, SceneState::of(scene_), scene_.render, scene_.image),
          pool_(threads) {}

    Image render(int frames, std::uint32_t firstFrame = 0) {
        const RenderSettings& s = scene_.render;
        const int w = scene_.image.width, h = scene_.image.height;
        const auto tiles = makeTiles(w, h, s.interleaveX, s.interleaveY, s.tileSize);
        Accumulator accumulator;
        accumulator.reset(w, h);
        FrameBuffer frame;
        std::vector<glm::vec3> filtered(std::size_t(w) * h);
        for (int f = 0; f < frames; ++f) {
            frame.reset(w, h);
            for (const Tile& t : tiles) {
                const proto::TileResult r =
                    renderer_.renderNow(pool_, firstFrame + std::uint32_t(f), t);
                frame.scatter(t, s.interleaveX, s.interleaveY, r.channels);
                shadowRays_ += r.stats.shadowRays;
            }
            discontinuityFilterRows(frame,
                                    {s.effectiveFilterX(), s.effectiveFilterY(),
                                     s.filterDepthThreshold, s.filterNormalThreshold},
                                    0, h, filtered);
            accumulator.addRows(filtered, 0, h);
            accumulator.endFrame();
        }
        Image image(w, h);
        accumulator.meanRows(image.pixels, 0, h);
        return image;
    }

    TileRenderer& renderer() { return renderer_; }
    const TraceableScene& traceable() const { return traceable_; }
    std::uint64_t shadowRays() const { return shadowRays_; }

  private:
    Scene scene_;
    EmbreeDevice device_;
    SceneGeometry geometry_;
    TraceableScene traceable_;
    TileRenderer renderer_;
    ThreadPool pool_;
    std::uint64_t shadowRays_ = 0;
};

inline glm::dvec3 meanOf(const Image& image) {
    glm::dvec3 sum(0.0);
    for (const auto& p : image.pixels) sum += glm::dvec3(p);
    return sum / double(image.pixels.size());
}

}  // namespace igi::testing
