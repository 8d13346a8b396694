#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include "render/FrameBuffer.h"

namespace igi {

/// The discontinuity buffer (paper, section 4.3): each pixel's irradiance is averaged with
/// that of the neighbours in a sizeX x sizeY window that lie on the same smooth surface, then
/// multiplied by the pixel's own reflectance (so texture detail stays sharp); the glossy
/// radiance is averaged over those of the same neighbours whose normal is nearly the pixel's
/// (glossyNormalThreshold), and the radiance that must not be filtered is added. With the
/// window the size of the interleaving pattern, every set P_k contributes to every pixel, which
/// removes the structured noise of interleaving.
struct DiscontinuityFilterSettings {
    int sizeX = 3;
    int sizeY = 3;
    /// A neighbour is continuous when |depth_q - depth_p| <= depthThreshold * depth_p (relative,
    /// so the test means the same at every scene scale) ...
    float depthThreshold = 0.05f;
    /// ... and dot(normal_p, normal_q) >= normalThreshold.
    float normalThreshold = 0.9f;
    /// The glossy radiance is averaged over the continuous neighbours whose normal is also
    /// within this cosine of the pixel's (2 degrees; the wire's normals are 8-bit octahedral,
    /// steps of 0.5 to 1 degree, so a flat surface's neighbours pass). Irradiance depends on the
    /// normal smoothly, over the whole hemisphere; glossy radiance follows the reflected
    /// direction, which turns twice as fast as the normal, through a lobe that may be a few
    /// degrees wide: averaged across normalThreshold's 26 degrees on a curved glossy surface
    /// it is a blur of the reflection, biased wherever the window is one-sided (toward a
    /// silhouette, or where the normal test cuts it), and too small per pixel for the
    /// progressive filter to find in a few hundred frames (docs/MATERIALS.md, "The spheres
    /// under studio.exr"). Flat glossy surfaces, where the interleaving's structured noise
    /// is, are filtered as before.
    float glossyNormalThreshold = 0.99939f;
};

/// First row or column of a window of `size` around `centre`: centred (leaning left or up for
/// even sizes), then shifted to lie inside [0, extent). A shifted window still covers `size`
/// consecutive columns, hence every interleaving cell, which a truncated one would not.
int filterWindowStart(int centre, int size, int extent);

/// Filters rows [rowBegin, rowEnd) of `frame` into `out` (width * height entries). At the
/// image's borders the window is shifted inward rather than cut, so that it still covers every
/// interleaving cell. Eight pixels at a time (RowFilter.h), the same bits as one at a time.
void discontinuityFilterRows(const FrameBuffer& frame, const DiscontinuityFilterSettings& settings,
                             int rowBegin, int rowEnd, std::vector<glm::vec3>& out);

/// The same rows without the buffer: reflectance * irradiance + glossy + unfiltered, each pixel
/// on its own (what the progressive filter of Accumulator compares the filtered frame with).
void compositeUnfilteredRows(const FrameBuffer& frame, int rowBegin, int rowEnd,
                             std::vector<glm::vec3>& out);

}  // namespace igi
