// igi-bench: how close a client comes to the hardware's limit. On one scene and one machine, side
// by side in one run, it measures
//   - raw Embree occlusion throughput: random shadow segments with rtcOccluded1 and in packets of
//     8 (rtcOccluded8), on the given number of threads;
//   - a client's throughput rendering whole frames of tiles (IGI, every ray counted);
// and reports the ratio. Results go to stdout as JSON.
#include <atomic>
#include <chrono>
#include <functional>
#include <iostream>

#include <embree3/rtcore.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "EmbreeDevice.h"
#include "SceneGeometry.h"
#include "ShadowSegments.h"
#include "TileRenderer.h"
#include "TraceableScene.h"
#include "render/Tile.h"
#include "scene/SceneLoader.h"
#include "scene/SceneState.h"
#include "util/ThreadPool.h"

namespace {

using Clock = std::chrono::steady_clock;
constexpr std::size_t kChunk = 4096;

double seconds(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// Calls chunk(c) for every chunk c < count on the pool's threads only, as the client renders
// tiles: ThreadPool::parallelFor would put the calling thread to work as well, one thread more
// than the client gets (which once made the raw figures look twice as fast on one thread).
void forEachChunkOnPool(std::size_t count, igi::ThreadPool& pool,
                        const std::function<void(std::size_t)>& chunk) {
    std::atomic<std::size_t> next{0};
    for (unsigned t = 0; t < pool.size(); ++t)
        pool.submit([&] {
            for (std::size_t c; (c = next.fetch_add(1)) < count;) chunk(c);
        });
    pool.waitIdle();
}

// Shadow rays per second through rtcOccluded1, one ray at a time.
double occluded1(RTCScene scene, const std::vector<igi::ShadowSegment>& segs, igi::ThreadPool& pool,
                 std::size_t& blocked) {
    std::atomic<std::size_t> hits{0};
    const auto start = Clock::now();
    forEachChunkOnPool((segs.size() + kChunk - 1) / kChunk, pool, [&](std::size_t c) {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        std::size_t local = 0;
        for (std::size_t i = c * kChunk; i < std::min(segs.size(), (c + 1) * kChunk); ++i) {
            RTCRay ray{};
            ray.org_x = segs[i].origin.x, ray.org_y = segs[i].origin.y,
            ray.org_z = segs[i].origin.z;
            ray.dir_x = segs[i].direction.x, ray.dir_y = segs[i].direction.y,
            ray.dir_z = segs[i].direction.z;
            ray.tnear = 0;
            ray.tfar = segs[i].length;
            ray.mask = 0xFFFFFFFFu;
            rtcOccluded1(scene, &context, &ray);
            local += ray.tfar < 0;
        }
        hits += local;
    });
    blocked = hits;
    return double(segs.size()) / seconds(start);
}

// Shadow rays per second through rtcOccluded8: packets of 8 consecutive segments.
double occluded8(RTCScene scene, const std::vector<igi::ShadowSegment>& segs,
                 igi::ThreadPool& pool) {
    const auto start = Clock::now();
    forEachChunkOnPool((segs.size() + kChunk - 1) / kChunk, pool, [&](std::size_t c) {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        const std::size_t end = std::min(segs.size(), (c + 1) * kChunk);
        for (std::size_t i = c * kChunk; i < end; i += 8) {
            alignas(32) int valid[8];
            alignas(32) RTCRay8 ray{};
            for (int j = 0; j < 8; ++j) {
                const std::size_t k = i + j;
                valid[j] = k < end ? -1 : 0;
                if (k >= end) continue;
                ray.org_x[j] = segs[k].origin.x, ray.org_y[j] = segs[k].origin.y,
                ray.org_z[j] = segs[k].origin.z;
                ray.dir_x[j] = segs[k].direction.x, ray.dir_y[j] = segs[k].direction.y,
                ray.dir_z[j] = segs[k].direction.z;
                ray.tnear[j] = 0;
                ray.tfar[j] = segs[k].length;
                ray.mask[j] = 0xFFFFFFFFu;
            }
            rtcOccluded8(valid, scene, &context, &ray);
        }
    });
    return double(segs.size()) / seconds(start);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"igi-bench: client throughput against raw Embree on the same scene and machine"};
    std::string sceneFile;
    unsigned threads = 0;
    std::size_t segments = 4'000'000;
    int frames = 4, width = 0, height = 0;
    bool allowOutsidePaths = false;
    app.add_option("--scene", sceneFile, "scene file or .obj")->required();
    app.add_flag("--allow-outside-paths", allowOutsidePaths,
                 "let the scene file name files outside its own folder");
    app.add_option("--threads", threads, "threads for both measurements (0: all)")
        ->capture_default_str();
    app.add_option("--segments", segments, "random shadow segments for the raw measurement")
        ->capture_default_str();
    app.add_option("--frames", frames, "frames the client renders")->capture_default_str();
    app.add_option("--width", width, "image width (0: the scene's)");
    app.add_option("--height", height, "image height (0: the scene's)");
    CLI11_PARSE(app, argc, argv);
    spdlog::set_level(spdlog::level::warn);
    try {
        igi::SceneLoadOptions loadOptions;
        loadOptions.allowOutsidePaths = allowOutsidePaths;
        igi::Scene scene = igi::loadSceneFile(sceneFile, loadOptions);
        if (width > 0) scene.image.width = width;
        if (height > 0) scene.image.height = height;
        igi::ThreadPool pool(threads > 0 ? threads : igi::ThreadPool::defaultThreads());
        igi::EmbreeDevice device;
        igi::SceneGeometry geometry(device, scene);
        igi::TraceableScene traceable(geometry);

        const auto segs = igi::randomShadowSegments(traceable, segments, 12345);
        std::size_t blocked = 0;
        occluded1(traceable.embreeScene(), segs, pool, blocked);  // warm up caches and threads
        const double raw1 = occluded1(traceable.embreeScene(), segs, pool, blocked);
        const double raw8 = occluded8(traceable.embreeScene(), segs, pool);

        igi::TileRenderer renderer(traceable, igi::SceneState::of(scene), scene.render, scene.image,
                                   igi::LightingContext{&scene, 0, 0, nullptr});
        const auto& s = scene.render;
        const auto tiles = igi::makeTiles(scene.image.width, scene.image.height, s.interleaveX,
                                          s.interleaveY, s.tileSize);
        std::uint64_t rays = 0, shadowRays = 0;
        const auto start = Clock::now();
        for (int f = 0; f < frames; ++f) {
            std::atomic<std::size_t> remaining{tiles.size()};
            std::mutex mutex;
            std::condition_variable done;
            for (std::uint32_t t = 0; t < tiles.size(); ++t) {
                renderer.render(pool, std::uint32_t(f), 0, t, tiles[t],
                                [&](igi::proto::TileResult&& r) {
                                    std::lock_guard lock(mutex);
                                    rays += r.stats.rays;
                                    shadowRays += r.stats.shadowRays;
                                    if (--remaining == 0) done.notify_all();
                                });
            }
            std::unique_lock lock(mutex);
            done.wait(lock, [&] { return remaining == 0; });
        }
        const double renderSeconds = seconds(start);
        const double clientShadow = double(shadowRays) / renderSeconds,
                     clientRays = double(rays) / renderSeconds;

        nlohmann::json out{{"scene", sceneFile},
                           {"triangles", traceable.triangleCount()},
                           {"threads", pool.size()},
                           {"segments", segs.size()},
                           {"segments_blocked", double(blocked) / double(segs.size())},
                           {"embree_occluded1_rays_per_second", raw1},
                           {"embree_occluded8_rays_per_second", raw8},
                           {"client_frames", frames},
                           {"client_width", scene.image.width},
                           {"client_height", scene.image.height},
                           {"client_seconds", renderSeconds},
                           {"client_rays_per_second", clientRays},
                           {"client_shadow_rays_per_second", clientShadow},
                           {"client_rays_over_embree_occluded1", clientRays / raw1}};
        std::cout << out.dump(2) << '\n';
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "igi-bench: " << e.what() << '\n';
        return 1;
    }
}
