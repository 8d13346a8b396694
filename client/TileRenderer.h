#pragma once

#include <cstdint>
#include <functional>
#include <memory>

#include "Messages.h"
#include "integrators/IgiIntegrator.h"
#include "integrators/PathIntegrator.h"
#include "lighting/LightingCache.h"
#include "lighting/LightingMethod.h"
#include "lighting/LightingSetBuilder.h"
#include "lights/Lights.h"
#include "render/Tile.h"
#include "scene/CameraModel.h"
#include "tracing/TraceableScene.h"
#include "util/ThreadPool.h"

namespace igi {

/// Renders tiles of one scene on all cores: each tile is cut into chunks (blocks of its pixels,
/// shaded together) that the pool's threads take as they come, so several tiles in flight keep
/// every core busy. The set
/// P_k / C_k of a tile comes from the cache (built by the first chunk that needs it).
class TileRenderer {
  public:
    /// Renders `scene`, a version whose camera and point lights `state` gives, lit by the
    /// method settings.gi names; `context` carries what a method that keeps lighting across
    /// epochs needs (the loaded scene and the previous epoch's history).
    TileRenderer(const TraceableScene& scene, const SceneState& state,
                 const RenderSettings& settings, const ImageSettings& image,
                 const LightingContext& context = {});

    using Done = std::function<void(proto::TileResult&&)>;

    /// Queues the tile's chunks on `pool`; `done` runs on the thread that finishes the last one.
    /// `accumulation` is the frame's place in its accumulation (TileAssign::accumulation).
    void render(ThreadPool& pool, std::uint32_t frame, std::uint32_t accumulation,
                std::uint32_t tileId, const Tile& tile, Done done);

    /// Renders a tile on `pool` and waits for it (tests and tools).
    proto::TileResult renderNow(ThreadPool& pool, std::uint32_t frame, const Tile& tile,
                                std::uint32_t accumulation = 0);

    LightingCache& cache() { return cache_; }
    const LightingSetBuilder& builder() const { return builder_; }
    const LightingMethod& method() const { return *method_; }
    const Lights& lights() const { return lights_; }
    const CameraModel& camera() const { return camera_; }

  private:
    struct TileJob;
    void renderChunk(TileJob& job, int chunk);

    const TraceableScene& scene_;
    RenderSettings settings_;
    ImageSettings image_;
    CameraModel camera_;
    Lights lights_;
    LightingSetBuilder builder_;
    std::unique_ptr<LightingMethod> method_;
    LightingCache cache_;
    IgiIntegrator igi_;
    PathIntegrator path_;
};

}  // namespace igi
