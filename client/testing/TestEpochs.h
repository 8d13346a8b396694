#pragma once

#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "SceneVersion.h"

namespace igi::testing {

/// A client's scene versions, one per epoch, each continuing the previous one's lighting as
/// ClientSession does (or, with `fresh`, starting from nothing, as a client that joins does),
/// for the tests of the lighting methods that keep state across epochs.
template <typename Method>
class Epochs {
  public:
    explicit Epochs(Scene scene) : scene_(std::move(scene)), geometry_(device_, scene_) {}

    /// The method of a new epoch in `state`, beginning at `firstFrame`.
    const Method& begin(const SceneState& state, std::uint32_t firstFrame = 0, bool fresh = false) {
        LightingContext c{&scene_, std::uint32_t(versions_.size()), firstFrame, nullptr};
        if (!versions_.empty() && !fresh)
            c.previous = versions_.back()->renderer.method().history(firstFrame);
        versions_.push_back(std::make_unique<SceneVersion>(c.epoch, geometry_, state, scene_.render,
                                                           scene_.image, c));
        const auto* m = dynamic_cast<const Method*>(&versions_.back()->renderer.method());
        EXPECT_NE(m, nullptr);
        return *m;
    }
    const Scene& scene() const { return scene_; }

  private:
    Scene scene_;
    EmbreeDevice device_;
    SceneGeometry geometry_;
    std::vector<std::unique_ptr<SceneVersion>> versions_;
};

}  // namespace igi::testing
