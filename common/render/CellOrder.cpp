#include "render/CellOrder.h"

#include <algorithm>

namespace igi {

CellOrder::CellOrder(int width, int cells)
    : width_(width), cells_(std::max(1, cells)), start_(std::size_t(cells_) + 1, 0) {
    for (int kx = 0; kx < cells_; ++kx) {
        const int columns = width > kx ? (width - kx + cells_ - 1) / cells_ : 0;
        start_[std::size_t(kx) + 1] = start_[std::size_t(kx)] + columns;
    }
}

int CellOrder::offset(int kx, int dx) const {
    // x = kx + c * n; x + dx = (kx + dx) mod n + (c + q) * n with q = floor((kx + dx) / n).
    const int k = kx + dx;
    const int q = k >= 0 ? k / cells_ : -((-k + cells_ - 1) / cells_);
    return start(k - q * cells_) + q - start(kx);
}

void toImageOrder(const CellOrder& order, const float* r, const float* g, const float* b,
                  glm::vec3* out) {
    const int n = order.cells();
    for (int kx = 0; kx < n; ++kx) {
        const int start = order.start(kx), count = order.count(kx);
        glm::vec3* column = out + kx;
        for (int c = 0; c < count; ++c)
            column[std::size_t(c) * std::size_t(n)] =
                glm::vec3(r[start + c], g[start + c], b[start + c]);
    }
}

}  // namespace igi
