#include "FrameCompositor.h"

#include <cstring>
#include <random>

#include <gtest/gtest.h>

#include "render/DiscontinuityFilter.h"

namespace igi {
namespace {

FrameBuffer noisyFrame(int w, int h, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    FrameBuffer f;
    f.reset(w, h);
    for (std::size_t p = 0; p < f.depth.size(); ++p) {
        const int x = int(p % std::size_t(w));
        f.depth[p] = x < w / 2 ? 2.0f : 3.0f;  // a depth edge, where the blur is biased
        f.normal[p] = glm::vec3(0, 0, 1);
        f.reflectance[p] = glm::vec3(0.6f);
        f.irradiance[p] = glm::vec3(x < w / 2 ? 1.0f : 4.0f) * (0.5f + u(rng));
        f.unfiltered[p] = u(rng) < 0.1f ? glm::vec3(u(rng)) : glm::vec3(0.0f);
    }
    return f;
}

// The compositor filters, accumulates and averages in one sweep over blocks of rows, on
// several threads, leaving the rows whose mean reads another block for a second sweep. The
// result must be the straightforward passes' (filter every row, add, end the frame, mean),
// frame after frame, bit for bit, at heights that cut blocks anywhere.
TEST(FrameCompositor, OneSweepEqualsTheSeparatePasses) {
    for (const int height : {5, 16, 17, 47}) {
        const int width = 29;
        RenderSettings settings;
        ThreadPool pool(3);
        FrameCompositor compositor(width, height, settings, pool);
        const DiscontinuityFilterSettings filter{
            settings.effectiveFilterX(), settings.effectiveFilterY(), settings.filterDepthThreshold,
            settings.filterNormalThreshold};
        Accumulator reference;
        reference.reset(width, height, true, filter.sizeX, filter.sizeY);
        std::vector<glm::vec3> filtered(std::size_t(width) * height), unfiltered(filtered.size()),
            mean(filtered.size());
        for (int frame = 0; frame < 6; ++frame) {
            const FrameBuffer f = noisyFrame(width, height, std::uint32_t(frame + 1));
            discontinuityFilterRows(f, filter, 0, height, filtered);
            compositeUnfilteredRows(f, 0, height, unfiltered);
            reference.addRows(filtered, unfiltered, 0, height);
            reference.endFrame();
            reference.meanRows(mean, 0, height);
            const Image& shown = compositor.composite(f);
            ASSERT_EQ(compositor.accumulatedFrames(), frame + 1);
            ASSERT_EQ(std::memcmp(shown.pixels.data(), mean.data(), mean.size() * sizeof(mean[0])),
                      0)
                << "height " << height << ", frame " << frame;
            ASSERT_EQ(std::memcmp(compositor.lastFrame().pixels.data(), filtered.data(),
                                  filtered.size() * sizeof(filtered[0])),
                      0);
        }
    }
}

}  // namespace
}  // namespace igi
