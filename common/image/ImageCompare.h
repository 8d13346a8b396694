#pragma once

#include "image/Image.h"

namespace igi {

/// How far an image is from a reference.
struct ImageDifference {
    /// Mean over pixels and channels of (a - r)^2 / (r^2 + 0.01): the relative MSE of rendering
    /// papers (Rousselle et al.); the 0.01 keeps black pixels from dominating.
    double relativeMse = 0;
    double rmse = 0;              ///< root mean squared error, linear units
    double meanRelativeBias = 0;  ///< mean(a) / mean(r) - 1 over all channels: brightness bias
    /// Relative error of block means: |mean_block(a) / mean_block(r) - 1| averaged over blocks of
    /// blockSize x blockSize pixels (noise averages out, bias stays).
    double blockRelativeError = 0;
    double ssim = 0;  ///< SSIM of the tone-mapped (sRGB, clipped) luminance, 1 = identical
    /// Fraction of the counted pixels whose luminance is more than kSpeckleRatio times the
    /// reference's at the same pixel. Counted are the pixels whose reference luminance is at
    /// least kSpeckleMinReference of the reference's mean luminance (0 if there is none).
    double speckle = 0;
};

/// relativeMse's 0.01: in the denominator (r^2 + 0.01), also of the master's estimate of it
/// (RowAccumulator::meanRow), so that the two are the same measure.
inline constexpr double kRelativeMseEpsilon = 0.01;
/// Speckle: a pixel brighter than this multiple of the reference (strictly more).
inline constexpr double kSpeckleRatio = 4.0;
/// Speckle ignores pixels whose reference luminance is below this fraction of the mean.
inline constexpr double kSpeckleMinReference = 0.01;

/// Compares `image` with `reference` (same size, else std::invalid_argument). `exposure` in stops
/// is applied before tone mapping for SSIM.
ImageDifference compareImages(const Image& image, const Image& reference, int blockSize = 8,
                              float exposure = 0.0f);

}  // namespace igi
