// The wire format on real renders: quantization must be invisible and the frame small.
#include <gtest/gtest.h>

#include "Codec.h"
#include "scene/SceneLoader.h"
#include "testing/TestScenes.h"
#include "util/TestPaths.h"

namespace igi {
namespace {

TEST(WireQuantization, ARenderedFrameSurvivesTheWireWithRelativeMseBelow1e4) {
    Scene scene = loadSceneFile(testing::sourceDir() / "scenes/cornell/cornell.json");
    scene.image.width = 320;
    scene.image.height = 240;
    testing::InProcessRenderer renderer(scene);
    ThreadPool pool(2);
    const RenderSettings& s = scene.render;
    const auto tiles =
        makeTiles(scene.image.width, scene.image.height, s.interleaveX, s.interleaveY, s.tileSize);
    FrameBuffer exact, wire;
    exact.reset(scene.image.width, scene.image.height);
    wire.reset(scene.image.width, scene.image.height);
    std::size_t bytes = 0, pixels = 0;
    for (std::uint32_t i = 0; i < tiles.size(); ++i) {
        proto::TileResult r = renderer.renderer().renderNow(pool, 0, tiles[i]);
        r.tileId = i;
        exact.scatter(tiles[i], s.interleaveX, s.interleaveY, r.channels);
        const auto encoded = proto::encodeMessage(r, 0, 0);
        bytes += encoded.size();
        pixels += std::size_t(r.channels.count);
        const auto header = proto::decodeHeader(
            std::span<const std::uint8_t, proto::kHeaderSize>(encoded.data(), proto::kHeaderSize));
        const auto back = std::get<proto::TileResult>(
            proto::decodeMessage(header, std::span(encoded).subspan(proto::kHeaderSize)));
        wire.scatter(tiles[i], s.interleaveX, s.interleaveY, back.channels);
    }
    const DiscontinuityFilterSettings filter{s.effectiveFilterX(), s.effectiveFilterY(),
                                             s.filterDepthThreshold, s.filterNormalThreshold};
    std::vector<glm::vec3> a(exact.depth.size()), b(exact.depth.size());
    discontinuityFilterRows(exact, filter, 0, exact.height, a);
    discontinuityFilterRows(wire, filter, 0, wire.height, b);
    double error = 0, energy = 0;
    for (std::size_t p = 0; p < a.size(); ++p)
        for (int c = 0; c < 3; ++c) {
            error += double(b[p][c] - a[p][c]) * double(b[p][c] - a[p][c]);
            energy += double(a[p][c]) * double(a[p][c]);
        }
    const double relativeMse = error / energy;
    const double bytesPerPixel = double(bytes) / double(pixels);
    std::printf("quantized frame: relative MSE %.3g, %.2f bytes per pixel (headers included)\n",
                relativeMse, bytesPerPixel);
    EXPECT_LT(relativeMse, 1e-4);
    EXPECT_LE(bytesPerPixel, 8.0);
}

}  // namespace
}  // namespace igi
