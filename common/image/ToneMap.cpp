#include "image/ToneMap.h"

#include <array>
#include <bit>
#include <cstring>

namespace igi {
namespace {

// starts[k]: the smallest positive float v with toneMapChannel(v, 1) >= k (k = 1..255); found
// by bisection over the bit patterns of positive floats, which order as the floats do.
std::array<float, 256> levelStarts() {
    std::array<float, 256> starts{};
    starts[0] = 0.0f;
    for (int k = 1; k < 256; ++k) {
        std::uint32_t lo = 0, hi = std::bit_cast<std::uint32_t>(2.0f);  // 2 maps to 255
        while (hi - lo > 1) {
            const std::uint32_t mid = lo + (hi - lo) / 2;
            if (toneMapChannel(std::bit_cast<float>(mid), 1.0f) >= k)
                hi = mid;
            else
                lo = mid;
        }
        starts[k] = std::bit_cast<float>(hi);
    }
    return starts;
}

// A coarse index into the levels: the level at the start of each of kBuckets equal steps of
// [0, 1]; from there a few comparisons with `starts` find the exact one.
constexpr int kBuckets = 4096;

struct LevelTable {
    std::array<float, 256> starts = levelStarts();
    std::array<std::uint8_t, kBuckets> bucketLevel{};
    LevelTable() {
        for (int b = 0; b < kBuckets; ++b) {
            const float v = float(b) / kBuckets;
            bucketLevel[b] = v > 0 ? toneMapChannel(v, 1.0f) : 0;
        }
    }
    std::uint8_t level(float v) const {
        if (!(v > 0)) return 0;  // and NaN
        if (v >= 1.0f) return 255;
        int k = bucketLevel[int(v * kBuckets)];
        while (k < 255 && v >= starts[k + 1]) ++k;
        return std::uint8_t(k);
    }
};

}  // namespace

std::vector<std::uint8_t> toneMap8(const Image& image, float exposureStops) {
    static const LevelTable table;
    const float scale = std::exp2(exposureStops);
    std::vector<std::uint8_t> bytes(image.pixels.size() * 3);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) bytes[3 * i + c] = table.level(image.pixels[i][c] * scale);
    return bytes;
}

}  // namespace igi
