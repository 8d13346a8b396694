#pragma once

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "scene/SceneState.h"

namespace igi {

/// One change to a scene's state, by index (the master resolves names). A scene update is an
/// ordered list of them; applying it to the state of epoch e gives the state of epoch e + 1.
struct CameraChange {
    Camera camera;
    bool operator==(const CameraChange&) const = default;
};
struct TransformChange {
    std::uint32_t mesh = 0;
    Transform transform;
    bool operator==(const TransformChange&) const = default;
};
struct PunctualLightChange {
    std::uint32_t light = 0;
    PunctualLight value;  ///< position, intensity, on (the name is not changed)
    bool operator==(const PunctualLightChange&) const = default;
};
struct QuadLightChange {
    std::uint32_t light = 0;
    QuadLight value;  ///< corner, edges, radiance, on (the name is not changed)
    bool operator==(const QuadLightChange&) const = default;
};
struct MaterialChange {
    std::uint32_t material = 0;
    Material value;  ///< every field but the name and the texture
    bool operator==(const MaterialChange&) const = default;
};

/// The environment's radiance (a constant sky's, or the factor its map is scaled by) and
/// rotation; its map is the scene's file, which no change carries.
struct EnvironmentChange {
    Environment value;
    bool operator==(const EnvironmentChange&) const = default;
};

/// Every render setting at once (a `settings` control command): the epoch it makes renders as
/// a session started with them at its first frame would, so a method that keeps lighting across
/// epochs starts afresh there.
struct SettingsChange {
    RenderSettings settings;
    bool operator==(const SettingsChange&) const = default;
};

using SceneChange =
    std::variant<CameraChange, TransformChange, PunctualLightChange, QuadLightChange,
                 MaterialChange, EnvironmentChange, SettingsChange>;

/// Whether `changes` change the render settings (the epoch they make starts lighting afresh).
bool changesSettings(const std::vector<SceneChange>& changes);

/// Applies changes in order. Throws std::invalid_argument naming the first change whose index
/// is out of range (the state is then unchanged).
void applyChanges(SceneState& state, const std::vector<SceneChange>& changes);

/// The changes that turn `from` into `to` (states of the same scene): only what differs.
std::vector<SceneChange> diffStates(const SceneState& from, const SceneState& to);

}  // namespace igi
