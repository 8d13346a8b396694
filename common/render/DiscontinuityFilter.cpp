#include "render/DiscontinuityFilter.h"

#include <algorithm>
#include <stdexcept>

#include "render/CellOrder.h"
#include "render/FrameRow.h"
#include "render/RowFilter.h"

namespace igi {

int filterWindowStart(int centre, int size, int extent) {
    const int start = centre - (size - 1) / 2;
    return std::clamp(start, 0, std::max(0, extent - size));
}

void discontinuityFilterRows(const FrameBuffer& f, const DiscontinuityFilterSettings& s,
                             int rowBegin, int rowEnd, std::vector<glm::vec3>& out) {
    if (s.sizeY > FilterWindow::kMaxRows) throw std::invalid_argument("filter window too tall");
    const CellOrder order(f.width, 1);  // image order: the rows are split as they are
    const bool glossy = f.live.has(kGlossy);
    std::vector<FrameRow> rows(std::size_t(std::max(1, s.sizeY)));  // row y in slot y % sizeY
    ShadedRow shaded;
    for (int y = rowBegin; y < rowEnd; ++y) {
        FilterWindow window;
        const int y0 = filterWindowStart(y, s.sizeY, f.height);
        window.count = std::min(f.height, y0 + s.sizeY) - y0;
        for (int k = 0; k < window.count; ++k) {
            FrameRow& row = rows[std::size_t(y0 + k) % rows.size()];
            if (row.y != y0 + k) splitRow(f, y0 + k, order, row);
            window.rows[k] = &row;
        }
        window.centre = &rows[std::size_t(y) % rows.size()];
        filterRow(window, order, s, glossy, false, shaded);
        toImageOrder(order, shaded[ShadedRow::kFr], shaded[ShadedRow::kFg], shaded[ShadedRow::kFb],
                     out.data() + std::size_t(y) * f.width);
    }
}

void compositeUnfilteredRows(const FrameBuffer& f, int rowBegin, int rowEnd,
                             std::vector<glm::vec3>& out) {
    for (std::size_t p = std::size_t(rowBegin) * f.width; p < std::size_t(rowEnd) * f.width; ++p)
        out[p] = f.reflectance[p] * f.irradiance[p] + f.glossy[p] + f.unfiltered[p];
}

}  // namespace igi
