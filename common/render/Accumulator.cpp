#include "render/Accumulator.h"

namespace igi {

void Accumulator::reset(int width, int height) {
    width_ = width;
    height_ = height;
    frames_ = 0;
    sum_.assign(std::size_t(width) * height * 3, 0.0);
}

void Accumulator::addRows(const std::vector<glm::vec3>& frame, int rowBegin, int rowEnd) {
    for (std::size_t p = std::size_t(rowBegin) * width_; p < std::size_t(rowEnd) * width_; ++p) {
        sum_[3 * p] += frame[p].x;
        sum_[3 * p + 1] += frame[p].y;
        sum_[3 * p + 2] += frame[p].z;
    }
}

void Accumulator::meanRows(std::vector<glm::vec3>& out, int rowBegin, int rowEnd) const {
    const double inv = frames_ > 0 ? 1.0 / frames_ : 0.0;
    for (std::size_t p = std::size_t(rowBegin) * width_; p < std::size_t(rowEnd) * width_; ++p)
        out[p] = glm::vec3(float(sum_[3 * p] * inv), float(sum_[3 * p + 1] * inv),
                           float(sum_[3 * p + 2] * inv));
}

}  // namespace igi
