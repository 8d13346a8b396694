#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "TraceableScene.h"
#include "sampling/Distribution1D.h"
#include "scene/Scene.h"

namespace igi {

/// A point chosen on a light source.
struct LightSample {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f};   ///< emitting side of an area light; unused for a point light
    glm::vec3 emitted{0.0f};  ///< radiance of an area light, intensity (W/sr) of a point light
    float pdf = 0;            ///< selection probability times 1/area (area lights), or selection
    bool isPoint = false;
};

/// Every light source of a scene: emissive triangles (from Ke materials and quad lights; zero-area
/// ones skipped, a face listed twice counted once) and point lights, chosen by emitted power so
/// that scenes with many lights spend their few samples on the lights that matter.
class Lights {
  public:
    /// The emissive triangles of `traceable` (quad lights included) and the point lights that
    /// are on.
    Lights(const TraceableScene& traceable, const std::vector<PointLight>& pointLights);

    bool empty() const { return distribution_.empty(); }
    std::size_t count() const { return emitters_.size(); }

    /// Chooses a light with uSelect (by power) and a point on it with uPoint. `uRemapped`, if
    /// given, receives uSelect rescaled within the chosen light: a fresh uniform number.
    LightSample sample(float uSelect, glm::vec2 uPoint, float* uRemapped = nullptr) const;

    /// Area-measure density with which sample() picks a point on the emissive triangle
    /// (mesh, triangle), for multiple importance sampling; 0 if it is not a light.
    float areaPdf(std::uint32_t mesh, std::uint32_t triangle) const;

    /// Total emitted power, summed luminance (for tests and statistics).
    double totalPower() const { return distribution_.total(); }

  private:
    struct Emitter {
        glm::vec3 p0{0.0f}, e1{0.0f}, e2{0.0f};  ///< triangle p0, p0+e1, p0+e2, or the point
        glm::vec3 normal{0.0f};
        glm::vec3 emitted{0.0f};
        float area = 0;
        bool isPoint = false;
    };

    std::vector<Emitter> emitters_;
    Distribution1D distribution_;
    std::unordered_map<std::uint64_t, std::uint32_t> triangleToEmitter_;
};

}  // namespace igi
