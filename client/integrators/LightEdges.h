#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "scene/CameraModel.h"

namespace igi {

class Lights;

/// The pixels that the outline of an emissive triangle may cross, as the camera sees it.
///
/// There one eye ray per frame finds the light rarely and very bright: a lamp a hundred times
/// brighter than the ceiling around it that covers 1 % of a pixel is seen in about one frame
/// of a hundred, so the pixel's mean jumps by the lamp's hundredth when it is. Such pixels
/// held most of the error of the interiors after 64 frames (docs/ACCURACY.md, "Light edges"),
/// and IgiIntegrator gathers the light seen directly there with rays of its own.
///
/// A pixel is marked when a triangle's projected edge passes within a pixel of it, whether or
/// not something hides the edge (marking too many costs rays, never accuracy). Edges behind the
/// camera are clipped away; a triangle seen from behind is marked too (its edge is still an
/// edge of what hides it). A function of the lights and the camera only: every client marks the
/// same pixels.
class LightEdges {
  public:
    LightEdges() = default;
    /// No pixel marked yet: addTriangle marks them.
    explicit LightEdges(const CameraModel& camera);
    /// The outlines of the emissive triangles of `lights`.
    LightEdges(const Lights& lights, const CameraModel& camera);
    /// Marks the outline of the triangle (a, b, c): for tests and for Lights' triangles alike.
    void addTriangle(glm::vec3 a, glm::vec3 b, glm::vec3 c);

    bool contains(int x, int y) const {
        return !mask_.empty() && mask_[std::size_t(y) * std::size_t(width_) + std::size_t(x)];
    }
    /// Marked pixels.
    std::size_t count() const { return count_; }
    bool empty() const { return count_ == 0; }

  private:
    void addSegment(float x0, float y0, float x1, float y1);
    void mark(int x, int y);

    CameraModel camera_{Camera{}, 1, 1};
    int width_ = 0, height_ = 0;
    std::vector<std::uint8_t> mask_;
    std::size_t count_ = 0;
};

}  // namespace igi
