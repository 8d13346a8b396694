#pragma once

#include <cstdint>

namespace igi {

/// How much a progressive quantity (the caustic gather radius squared, the clamp distance
/// squared) shrinks by the accumulated frame i (0 = the first frame after a change):
///   r_i^2 / r_0^2 = prod_{k=1..i} (k + alpha) / (k + 1)
/// (progressive photon mapping as Knaus and Zwicker 2011 write it, alpha in (0, 1); it falls
/// like i^(alpha - 1), so the bias of the running mean vanishes while its variance still falls).
/// alpha <= 0 means "do not shrink". Computed by plain double multiplications, not lgamma, so
/// that every client computes the same bits from the same i.
inline double progressiveScale(double alpha, std::uint32_t i) {
    if (!(alpha > 0)) return 1.0;
    double scale = 1.0;
    for (std::uint32_t k = 1; k <= i; ++k) scale *= (double(k) + alpha) / (double(k) + 1.0);
    return scale;
}

}  // namespace igi
