#include "render/TileRegions.h"

#include <algorithm>

namespace igi {

TileRegions::TileRegions(int width, int height, int n, int m, int tileSize)
    : width_(width),
      height_(height),
      regionWidth_(std::max(1, tileSize * n)),
      regionHeight_(std::max(1, tileSize * m)),
      columns_((width + regionWidth_ - 1) / regionWidth_) {
    const int rows = (height + regionHeight_ - 1) / regionHeight_;
    rendered_.assign(std::size_t(columns_) * std::size_t(rows), 1);
}

Tile TileRegions::rectangle(int region) const {
    Tile t;
    t.x0 = (region % columns_) * regionWidth_;
    t.y0 = (region / columns_) * regionHeight_;
    t.width = std::min(regionWidth_, width_ - t.x0);
    t.height = std::min(regionHeight_, height_ - t.y0);
    return t;
}

bool TileRegions::all() const {
    return std::all_of(rendered_.begin(), rendered_.end(), [](std::uint8_t r) { return r != 0; });
}

int TileRegions::renderedCount() const {
    return int(
        std::count_if(rendered_.begin(), rendered_.end(), [](std::uint8_t r) { return r != 0; }));
}

void TileRegions::rowMask(int y, const CellOrder& order, float* out, std::size_t padding) const {
    const std::size_t rowStart = std::size_t(y / regionHeight_) * std::size_t(columns_);
    for (int x = 0; x < order.width(); ++x)
        out[order.position(x)] = rendered_[rowStart + std::size_t(x / regionWidth_)] ? 1.0f : 0.0f;
    std::fill_n(out + order.width(), padding, 1.0f);
}

}  // namespace igi
