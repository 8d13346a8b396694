#pragma once

#include <cstdint>
#include <memory>

#include "TileRenderer.h"
#include "scene/SceneState.h"
#include "tracing/SceneGeometry.h"
#include "tracing/TraceableScene.h"

namespace igi {

/// One epoch of a scene on a client: its state and everything rendering needs that depends on
/// it (instances, materials, lights, light sets, camera). Tiles hold the version of their own
/// epoch, so a newer version can arrive while older tiles finish: a frame never mixes epochs.
struct SceneVersion {
    /// `context`: the loaded scene and the previous epoch's lighting history, for methods that
    /// keep lighting across epochs (its epoch is set here).
    SceneVersion(std::uint32_t epoch, const SceneGeometry& geometry, SceneState state,
                 const RenderSettings& settings, const ImageSettings& image,
                 LightingContext context = {})
        : epoch(epoch),
          state(std::move(state)),
          traceable(geometry, this->state),
          renderer(traceable, this->state, settings, image, withEpoch(std::move(context), epoch)) {}

    static LightingContext withEpoch(LightingContext c, std::uint32_t epoch) {
        c.epoch = epoch;
        return c;
    }

    std::uint32_t epoch;
    SceneState state;
    TraceableScene traceable;
    TileRenderer renderer;
};

}  // namespace igi
