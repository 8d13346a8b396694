#include "render/CellOrder.h"

#include <algorithm>
#include <cstdint>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

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

void toImageOrderStreamed(const CellOrder& order, const float* r, const float* g, const float* b,
                          glm::vec3* out) {
#if defined(__SSE2__)
    // Interleaved in a row that stays in the cache, then streamed out 16 bytes at a time.
    thread_local std::vector<glm::vec3> row;
    row.resize(std::size_t(order.width()));
    toImageOrder(order, r, g, b, row.data());
    const float* in = &row.data()->x;
    float* to = &out->x;
    std::size_t n = row.size() * 3;
    for (; n > 0 && reinterpret_cast<std::uintptr_t>(to) % 16 != 0; --n) *to++ = *in++;
    for (; n >= 4; n -= 4, in += 4, to += 4) _mm_stream_ps(to, _mm_loadu_ps(in));
    for (; n > 0; --n) *to++ = *in++;
#else
    toImageOrder(order, r, g, b, out);
#endif
}

void streamedStoresDone() {
#if defined(__SSE2__)
    _mm_sfence();
#endif
}

}  // namespace igi
