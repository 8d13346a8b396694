#pragma once

#include "math/Lanes.h"
#include "render/CellOrder.h"
#include "render/DiscontinuityFilter.h"
#include "render/FrameRow.h"
#include "render/RowPlanes.h"

namespace igi {

/// What the discontinuity buffer makes of one frame row, in cell order: the filtered pixel
/// (reflectance * filtered irradiance + filtered glossy + unfiltered) and, when asked for, the
/// pixel without the buffer (reflectance * irradiance + glossy + unfiltered), which the
/// progressive filter compares it with.
struct ShadedRow : RowPlanes<6> {
    enum Plane { kFr, kFg, kFb, kUr, kUg, kUb };
};

/// The rows that the window of row y reads: rows y0 .. y0 + count - 1 of the frame
/// (filterWindowStart), each in cell order, and row y itself.
struct FilterWindow {
    static constexpr int kMaxRows = 32;
    const FrameRow* rows[kMaxRows] = {};
    int count = 0;
    const FrameRow* centre = nullptr;
};

/// Filters row window.centre->y into `out`, bit for bit what discontinuityFilterRows writes for
/// it (in cell order instead of image order). `glossy`: whether the frame's glossy plane is
/// live (when not, its arrays are not read and count as zero). `unfiltered`: also write the
/// pixel without the buffer. Eight pixels at a time, in the code `isa` names.
void filterRow(const FilterWindow& window, const CellOrder& order,
               const DiscontinuityFilterSettings& settings, bool glossy, bool unfiltered,
               ShadedRow& out, lanes::Isa isa = lanes::bestIsa());

}  // namespace igi
