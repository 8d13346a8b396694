#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "scene/Scene.h"
#include "scene/SceneState.h"

namespace igi {

/// A keyframed animation of a scene's changeable state (docs/ANIMATION.md): the camera, mesh
/// transforms, lights, materials and the environment, each property keyed on its own. Immutable
/// once parsed; copies share the parsed keyframes.
class Animation {
  public:
    /// The largest keyframe index a file may use: every frame between keyframes is checked at
    /// load time, which must stay cheap.
    static constexpr std::uint32_t kMaxFrame = 1000000;

    /// An animation that changes nothing.
    Animation();

    /// Parses an animation file's text; names are resolved against `scene` (mesh names, light
    /// names, material names). Throws SceneError naming the file and the JSON path, also when
    /// an interpolated frame would have an unusable camera, quad light or scale (with the
    /// scene's own values for what the animation does not key).
    static Animation parse(const std::string& text, const std::string& fileName,
                           const Scene& scene);
    static Animation load(const std::filesystem::path& file, const Scene& scene);

    /// The state at `frame`: `base` with every animated property set to its value at that
    /// frame. Animated materials are scaled down where diffuse + specular would exceed 1. An
    /// object that this base would make unusable (a camera with no view direction, a quad
    /// light with no area: possible only with a base other than the scene's own) keeps its
    /// base value. A pure function of its arguments.
    SceneState stateAt(std::uint32_t frame, const SceneState& base) const;

    bool empty() const;
    std::uint32_t lastKeyFrame() const;  ///< the largest keyframe index (0 if empty)

  private:
    struct Tracks;
    std::shared_ptr<const Tracks> tracks_;
};

}  // namespace igi
