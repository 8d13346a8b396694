// igi-composite-bench: what the master spends per pixel of a frame, stage by stage, on one
// thread: reading the tile results, decompressing their codes into the frame (zstd,
// CodedFrame), and dequantizing, filtering, accumulating and averaging them
// (FrameCompositor), as the master does. The frame is synthetic but shaped like the
// default scene's (a room of flat walls and a sphere, 3 x 3 interleaved irradiance with noise,
// a mirror's unfiltered radiance in one region), cut into the master's tiles and encoded as
// clients send them. Unlike a replay run (scripts/bench_performance.sh, section 4), nothing
// else runs: the figures isolate the master's per-pixel work from the network and the clients.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <random>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/geometric.hpp>

#include "ByteReader.h"
#include "ByteWriter.h"
#include "ChannelCodec.h"
#include "CodedFrame.h"
#include "FrameCompositor.h"
#include "TileCodes.h"
#include "render/Tile.h"
#include "util/ThreadPool.h"

namespace {

using Clock = std::chrono::steady_clock;
using namespace igi;

/// The planes of pixel (x, y) of a w x h image: a box seen from inside, a sphere in front.
void syntheticPixel(int x, int y, int w, int h, std::mt19937& rng, glm::vec3& irradiance,
                    glm::vec3& reflectance, glm::vec3& normal, float& depth,
                    glm::vec3& unfiltered) {
    std::normal_distribution<float> noise(0.0f, 0.15f);
    const float u = (x + 0.5f) / w - 0.5f, v = (y + 0.5f) / h - 0.5f;
    const float r2 = (u + 0.15f) * (u + 0.15f) + (v - 0.15f) * (v - 0.15f);
    // Interleaving: each of the 3 x 3 cells has its own light sets, hence its own bias.
    const float cell = 0.85f + 0.05f * float((x % 3) + 3 * (y % 3)) / 4.0f;
    if (r2 < 0.04f) {  // the sphere
        normal = glm::normalize(glm::vec3(u + 0.15f, v - 0.15f, -std::sqrt(0.04f - r2)));
        depth = 2.5f - 2.0f * std::sqrt(0.04f - r2);
        reflectance = glm::vec3(0.7f, 0.7f, 0.65f);
        unfiltered = u > -0.1f ? glm::vec3(0.4f, 0.38f, 0.3f) * (1.0f + noise(rng)) : glm::vec3(0);
    } else if (std::abs(u) > 0.35f) {  // the side walls
        normal = glm::vec3(u > 0 ? -1.0f : 1.0f, 0.0f, 0.0f);
        depth = 3.0f + 4.0f * (0.5f - std::abs(u));
        reflectance = u > 0 ? glm::vec3(0.14f, 0.45f, 0.09f) : glm::vec3(0.63f, 0.06f, 0.04f);
        unfiltered = glm::vec3(0.0f);
    } else {  // back wall, floor and ceiling
        normal = std::abs(v) > 0.35f ? glm::vec3(0.0f, v > 0 ? -1.0f : 1.0f, 0.0f)
                                     : glm::vec3(0.0f, 0.0f, -1.0f);
        depth = std::abs(v) > 0.35f ? 3.0f + 4.0f * (0.5f - std::abs(v)) : 4.0f;
        reflectance = glm::vec3(0.73f, 0.71f, 0.68f);
        unfiltered = glm::vec3(0.0f);
    }
    irradiance = glm::vec3(1.2f, 1.1f, 0.9f) * cell * std::max(0.0f, 1.0f + noise(rng));
}

/// Every tile of a w x h frame as the master receives it: encoded channels.
std::vector<std::vector<std::uint8_t>> syntheticTiles(int w, int h, const RenderSettings& s,
                                                      const std::vector<Tile>& tiles) {
    std::mt19937 rng(7);
    std::vector<std::vector<std::uint8_t>> wire;
    for (const Tile& t : tiles) {
        TileChannels c;
        c.resize(t.pixelCount(s.interleaveX, s.interleaveY),
                 kIrradiance | kReflectance | kNormal | kDepth | kUnfiltered);
        for (int i = 0; i < c.count; ++i)
            syntheticPixel(t.pixelX(i, s.interleaveX), t.pixelY(i, s.interleaveX, s.interleaveY), w,
                           h, rng, c.irradiance[i], c.reflectance[i], c.normal[i], c.depth[i],
                           c.unfiltered[i]);
        std::vector<std::uint8_t> bytes;
        proto::ByteWriter out(bytes);
        proto::writeTileChannels(out, c);
        wire.push_back(std::move(bytes));
    }
    return wire;
}

double seconds(Clock::time_point since) {
    return std::chrono::duration<double>(Clock::now() - since).count();
}

double threadCpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"igi-composite-bench: the master's per-pixel work on one thread, by stage"};
    int width = 640, height = 480, frames = 40, rounds = 3;
    app.add_option("--width", width, "image width")
        ->capture_default_str()
        ->check(CLI::Range(3, 8192));
    app.add_option("--height", height, "image height")
        ->capture_default_str()
        ->check(CLI::Range(3, 8192));
    app.add_option("--frames", frames, "frames per round")
        ->capture_default_str()
        ->check(CLI::Range(1, 100000));
    app.add_option("--rounds", rounds, "rounds (the fastest is printed)")
        ->capture_default_str()
        ->check(CLI::Range(1, 100));
    CLI11_PARSE(app, argc, argv);

    RenderSettings settings;  // the paper's: 3 x 3 interleaving, accumulation, progressive filter
    const auto tiles =
        makeTiles(width, height, settings.interleaveX, settings.interleaveY, settings.tileSize);
    const auto wire = syntheticTiles(width, height, settings, tiles);

    // One worker, and everything runs on it: the master's --threads 1.
    ThreadPool pool(1);
    double best[3] = {1e30, 1e30, 1e30}, bestCpu = 1e30;
    pool.submit([&] {
        FrameCompositor compositor(width, height, settings, pool);
        std::vector<proto::CodedFrame> buffers(2);  // the master keeps two frames or more open
        for (int r = 0; r < rounds; ++r) {
            double t[2] = {0, 0};
            const double cpuStart = threadCpuSeconds();
            compositor.resetAccumulation();
            for (int f = 0; f < frames; ++f) {
                proto::CodedFrame& frame = buffers[std::size_t(f) % buffers.size()];
                frame.reuse(width, height, settings.interleaveX, settings.interleaveY,
                            settings.tileSize);
                // Tile by tile, as the master does: decompressed into the frame, still coded.
                auto start = Clock::now();
                for (std::size_t i = 0; i < tiles.size(); ++i) {
                    proto::ByteReader in(wire[i], "TileResult");
                    frame.scatter(tiles[i], proto::readTileCodes(in));
                }
                t[0] += seconds(start);
                start = Clock::now();
                compositor.composite(frame);
                t[1] += seconds(start);
            }
            bestCpu = std::min(bestCpu, threadCpuSeconds() - cpuStart);
            for (int k = 0; k < 2; ++k) best[k] = std::min(best[k], t[k]);
            best[2] = std::min(best[2], t[0] + t[1]);
        }
    });
    pool.waitIdle();
    const double pixels = double(width) * height * frames;
    const char* names[3] = {"decode (zstd, into the frame)",
                            "dequantize + filter + accumulate + mean", "total"};
    std::printf("%d x %d, %d frames a round, best of %d rounds, one thread\n", width, height,
                frames, rounds);
    for (int k = 0; k < 3; ++k)
        std::printf("%-40s %6.1f ns/pixel\n", names[k], best[k] * 1e9 / pixels);
    // On a shared machine the wall clock counts the time others held the core; the thread's
    // CPU time does not (nor does it count what they did to its caches).
    std::printf("%-40s %6.1f ns/pixel\n", "total, thread CPU time", bestCpu * 1e9 / pixels);
    std::printf("master ceiling: %.1f M pixels/s (%.1f fps)\n", pixels / best[2] * 1e-6,
                frames / best[2]);
    return 0;
}
