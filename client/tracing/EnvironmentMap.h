#pragma once

#include <memory>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "sampling/Distribution1D.h"
#include "scene/Environment.h"
#include "scene/Texture.h"

namespace igi {

/// The scene's environment as a light: its radiance in every direction (each texel of a map
/// constant over its patch of the sphere, as with Blender's "Closest" interpolation) and
/// directions chosen in proportion to luminance times solid angle, so that a map with one
/// texel 1e6 times the rest sends nearly every sample there. Built once per scene; copies
/// share the sampling tables.
class EnvironmentMap {
  public:
    EnvironmentMap() = default;  ///< none: black
    EnvironmentMap(const Environment& environment, const std::vector<Texture>& textures);

    /// The environment as `changed` describes it (a live change: another radiance factor or
    /// rotation, the same map). A factor proportional to the one the tables were built with
    /// keeps the tables: luminance is linear, so the density is the same and only the
    /// radiance and the mean luminance scale; a rotation turns the mapping alone. Any other
    /// factor (another colour balance, or from black) builds tables of its own.
    EnvironmentMap changedTo(const Environment& changed,
                             const std::vector<Texture>& textures) const;
    /// What this environment was made from.
    const Environment& description() const { return environment_; }

    bool present() const { return present_; }

    /// Radiance arriving from the unit direction `toSky` (pointing away from the scene).
    glm::vec3 radiance(glm::vec3 toSky) const;

    struct Sample {
        glm::vec3 toSky{0.0f};
        glm::vec3 radiance{0.0f};
        float pdf = 0;  ///< solid angle
    };
    Sample sample(glm::vec2 u) const;
    /// The solid-angle density with which sample() picks `toSky`.
    float pdf(glm::vec3 toSky) const;

    /// Mean luminance over the sphere: the irradiance of a plane under it is pi times this
    /// (for a constant sky), and the power through a disk of area A is 4 pi A times it.
    float meanLuminance() const { return meanLuminance_; }

  private:
    /// The texel (column, row) that `toSky` looks at.
    glm::ivec2 texelOf(glm::vec3 toSky) const;
    glm::vec3 texel(glm::ivec2 t) const;
    /// Solid angle of the texels of row `row`.
    float texelSolidAngle(int row) const;

    /// A map's sampling tables, for the factor they were built with.
    struct Tables {
        Distribution1D rows;                  ///< by each row's luminance times solid angle
        std::vector<Distribution1D> columns;  ///< within each row, by luminance
        glm::vec3 factor{0.0f};
        float meanLuminance = 0.0f;
    };

    Environment environment_;
    bool present_ = false;
    glm::vec3 factor_{0.0f};
    const Texture* map_ = nullptr;
    float rotateDeg_ = 0.0f;
    float meanLuminance_ = 0.0f;
    std::shared_ptr<const Tables> tables_;  ///< with a map
};

}  // namespace igi
