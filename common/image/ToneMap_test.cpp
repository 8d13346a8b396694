#include "image/ToneMap.h"

#include <bit>
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

namespace igi {
namespace {

// toneMap8 answers from a table; it must be toneMapChannel bit for bit, which the PNG output
// used per channel before, at every level's edges above all.
TEST(ToneMap8, EqualsToneMapChannelEverywhere) {
    std::vector<float> values = {0.0f,
                                 -1.0f,
                                 1e-30f,
                                 1.0f,
                                 0.999999f,
                                 2.0f,
                                 1e30f,
                                 std::numeric_limits<float>::infinity(),
                                 std::numeric_limits<float>::quiet_NaN()};
    // Around each level's first value: bisect as the table does, then a few ulps either side.
    for (int k = 1; k < 256; ++k) {
        std::uint32_t lo = 0, hi = std::bit_cast<std::uint32_t>(2.0f);
        while (hi - lo > 1) {
            const std::uint32_t mid = lo + (hi - lo) / 2;
            (toneMapChannel(std::bit_cast<float>(mid), 1.0f) >= k ? hi : lo) = mid;
        }
        for (int d = -3; d <= 3; ++d) values.push_back(std::bit_cast<float>(hi + d));
    }
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> uniform(0.0f, 1.2f);
    for (int i = 0; i < 20000; ++i) values.push_back(uniform(rng) * uniform(rng));

    for (float exposure : {0.0f, -3.0f, 2.5f}) {
        Image image(int(values.size()), 1);
        for (std::size_t i = 0; i < values.size(); ++i)
            image.pixels[i] = glm::vec3(values[i], 0.5f * values[i], values[i] + 0.01f);
        const std::vector<std::uint8_t> bytes = toneMap8(image, exposure);
        const float scale = std::exp2(exposure);
        ASSERT_EQ(bytes.size(), 3 * values.size());
        for (std::size_t i = 0; i < values.size(); ++i)
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ(bytes[3 * i + c], toneMapChannel(image.pixels[i][c], scale))
                    << "value " << image.pixels[i][c] << " exposure " << exposure;
    }
}

}  // namespace
}  // namespace igi
