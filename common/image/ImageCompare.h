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
};

/// Compares `image` with `reference` (same size, else std::invalid_argument). `exposure` in stops
/// is applied before tone mapping for SSIM.
ImageDifference compareImages(const Image& image, const Image& reference, int blockSize = 8,
                              float exposure = 0.0f);

}  // namespace igi
