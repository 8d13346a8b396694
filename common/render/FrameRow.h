#pragma once

#include "render/CellOrder.h"
#include "render/FrameBuffer.h"
#include "render/RowPlanes.h"

namespace igi {

/// One row of a frame's planes as the compositor's kernels read them: a float array per
/// component, in cell order. Filled from a FrameBuffer (splitRow) or decoded from the tiles'
/// wire codes (proto::CodedFrame::decodeRow).
struct FrameRow : RowPlanes<16> {
    /// Depth; normal x, y, z; irradiance R, G, B; glossy R, G, B (read only when the frame's
    /// glossy plane is live); reflectance R, G, B; unfiltered R, G, B.
    enum Plane {
        kDepth,
        kNx,
        kNy,
        kNz,
        kEr,
        kEg,
        kEb,
        kGr,
        kGg,
        kGb,
        kRr,
        kRg,
        kRb,
        kUr,
        kUg,
        kUb
    };
    int y = -1;  ///< the frame row it holds
};

/// Copies row y of `frame` into `row` in `order`; the glossy plane only when it is live.
void splitRow(const FrameBuffer& frame, int y, const CellOrder& order, FrameRow& row);

}  // namespace igi
