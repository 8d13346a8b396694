#pragma once

#include <cstdint>
#include <functional>
#include <memory>

#include "Messages.h"
#include "integrators/IgiIntegrator.h"
#include "integrators/PathIntegrator.h"
#include "lighting/IgiLighting.h"
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

    /// The sets of the accumulated frames (and of every frame where the first frame's settings
    /// are the same, RenderSettings::firstFrameSettings).
    LightingCache& cache() { return cache_; }
    /// The sets a frame at `accumulation` is rendered with.
    LightingCache& cacheFor(std::uint32_t accumulation) {
        return rendersFirstFrame(accumulation) ? firstFrame_->cache : cache_;
    }
    /// Forgets both caches' sets of frames before `frame`.
    void evictBefore(std::uint32_t frame) {
        cache_.evictBefore(frame);
        if (firstFrame_) firstFrame_->cache.evictBefore(frame);
    }
    const LightingSetBuilder& builder() const { return builder_; }
    /// The settings of the first frame after a change (RenderSettings::firstFrameSettings).
    const RenderSettings& firstFrameSettings() const {
        return firstFrame_ ? firstFrame_->settings : settings_;
    }
    bool firstFrameDiffers() const { return firstFrame_ != nullptr; }
    const LightingMethod& method() const { return *method_; }
    const Lights& lights() const { return lights_; }
    const CameraModel& camera() const { return camera_; }

  private:
    struct TileJob;
    /// What IGI renders its first frame after a change with where that frame's settings are
    /// not the accumulated frames' (RenderSettings::firstFrameDivisor): a builder, sets and an
    /// integrator of their own, over the same scene, lights and camera (and the accumulated
    /// frames' integrator's light edges). The frame is then the first frame of a session
    /// started with those settings, bit for bit.
    struct FirstFrame {
        FirstFrame(const TraceableScene& scene, const Lights& lights,
                   const RenderSettings& settings, const IgiIntegrator& accumulated)
            : settings(settings),
              builder(scene, lights, settings),
              method(builder),
              cache(method),
              igi(accumulated, settings) {}
        RenderSettings settings;
        LightingSetBuilder builder;
        IgiLighting method;
        LightingCache cache;
        IgiIntegrator igi;
    };
    void renderChunk(TileJob& job, int chunk);
    /// Whether a frame at `accumulation` is rendered with firstFrame_.
    bool rendersFirstFrame(std::uint32_t accumulation) const {
        return accumulation == 0 && firstFrame_ != nullptr;
    }

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
    std::unique_ptr<FirstFrame> firstFrame_;  ///< null where the first frame is like the others
};

}  // namespace igi
