#pragma once

// The changeable properties of each kind of scene object (camera, transform, punctual light,
// quad light, material, environment) as JSON keys: how one is read, how it blends between two
// values, and when a whole value is unusable. Animation keyframes and control commands both read
// through here, so a key means the same, with the same ranges and messages, in both (and as in
// scene files).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "scene/Camera.h"
#include "scene/Environment.h"
#include "scene/Light.h"
#include "scene/Material.h"
#include "scene/Transform.h"

namespace igi {

class JsonNode;

/// Which properties a JSON object gave: bit i is property i of the kind's table.
using PropertyMask = std::uint32_t;

/// One settable property of a `T`.
template <typename T>
struct Property {
    const char* key;  ///< the JSON key
    bool steps;       ///< booleans and kinds jump; numbers and vectors interpolate
    /// Reads the JSON value (checking its type and range) into the field.
    void (*read)(const JsonNode& node, T& value);
    /// out.field = the field blended from a (t = 0) to b (t = 1); stepping ones copy a's.
    void (*blend)(const T& a, const T& b, float t, T& out);
};

/// Why a whole value is unusable, and the keys whose values together cause it (an error names
/// the first of them that the JSON gives).
struct PropertyProblem {
    std::vector<const char*> keys;
    std::string message;
};

/// The properties of a kind, in bit order, and its whole-value check.
template <typename T>
struct PropertyTable {
    const char* kind;  ///< "camera", "object", ... for messages
    std::vector<Property<T>> properties;
    std::optional<PropertyProblem> (*problem)(const T& value);

    /// The bit of `key`, or -1.
    int indexOf(const std::string& key) const;
};

template <typename T>
const PropertyTable<T>& propertyTable();
template <>
const PropertyTable<Camera>& propertyTable<Camera>();
template <>
const PropertyTable<Transform>& propertyTable<Transform>();
template <>
const PropertyTable<PunctualLight>& propertyTable<PunctualLight>();
template <>
const PropertyTable<QuadLight>& propertyTable<QuadLight>();
template <>
const PropertyTable<Material>& propertyTable<Material>();
template <>
const PropertyTable<Environment>& propertyTable<Environment>();

/// Applies the properties that `node` (an object) gives onto `value` and returns which it gave.
/// Keys that are neither properties of T nor in `extraKeys` are errors naming them.
template <typename T>
PropertyMask applyProperties(const JsonNode& node, T& value,
                             const std::vector<std::string>& extraKeys);

/// Throws SceneError if `value` (after `node`'s properties were applied) is unusable, at the
/// path of the first responsible key that `node` gives (else at `node`).
template <typename T>
void requireUsable(const JsonNode& node, const T& value);

/// The largest fraction of light a material reflects in one channel (diffuse plus its specular
/// part); glass gives 0 (its diffuse and specular are not used).
float reflectedPeak(const Material& m);

/// Scales diffuse and specular down so that reflectedPeak(m) <= 1, as the scene loader does
/// (without its warning: callers decide whether to warn). Returns whether it scaled.
bool scaleToConserveEnergy(Material& m);

}  // namespace igi
