#pragma once

#include <cstddef>
#include <vector>

namespace igi {

/// `Planes` float arrays of one frame row, `width` entries each (in cell order, CellOrder.h),
/// kept in one allocation. Each array is followed by kPadding floats that kernels working eight
/// lanes at a time may write past the end and read back (zero until then), and the arrays are
/// staggered so that the same entry of different planes does not fall into one cache set.
template <int Planes>
class RowPlanes {
  public:
    static constexpr int kPadding = 16;

    void resize(int width) {
        if (width == width_) return;
        width_ = width;
        // Rounded to a cache line, plus one: plane k starts k lines off a 4 KB boundary.
        stride_ = (std::size_t(width) + kPadding + 15) / 16 * 16 + 16;
        storage_.assign(stride_ * Planes, 0.0f);
    }
    int width() const { return width_; }
    float* operator[](int plane) { return storage_.data() + stride_ * std::size_t(plane); }
    const float* operator[](int plane) const {
        return storage_.data() + stride_ * std::size_t(plane);
    }

  private:
    int width_ = -1;
    std::size_t stride_ = 0;
    std::vector<float> storage_;
};

}  // namespace igi
