#include "render/FrameRow.h"

namespace igi {

void splitRow(const FrameBuffer& f, int y, const CellOrder& order, FrameRow& row) {
    row.resize(f.width);
    const bool glossy = f.live.has(kGlossy);
    const std::size_t base = std::size_t(y) * std::size_t(f.width);
    auto put = [&](int plane, glm::vec3 v, int i) {
        row[plane][i] = v.x, row[plane + 1][i] = v.y, row[plane + 2][i] = v.z;
    };
    for (int x = 0; x < f.width; ++x) {
        const std::size_t p = base + std::size_t(x);
        const int i = order.position(x);
        row[FrameRow::kDepth][i] = f.depth[p];
        put(FrameRow::kNx, f.normal[p], i);
        put(FrameRow::kEr, f.irradiance[p], i);
        put(FrameRow::kRr, f.reflectance[p], i);
        put(FrameRow::kUr, f.unfiltered[p], i);
        if (glossy) put(FrameRow::kGr, f.glossy[p], i);
    }
    row.y = y;
}

}  // namespace igi
